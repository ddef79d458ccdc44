#include "replay/replay_run.h"

#include <sys/resource.h>
#include <sys/stat.h>
#include <unistd.h>

#include <algorithm>
#include <cassert>
#include <cerrno>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <memory>

#include "formats/graph_tsv.h"
#include "formats/replay_dir.h"
#include "formats/text_rows.h"

namespace atlas::replay {
namespace {

struct TimingRow {
  int64_t step = 0;
  Time stamp{};
  int frames = 0;
  int hypotheses = 0;
  FrameId dominant = kNoFrame;
  int64_t step_ns = 0;
};

struct HypothesisRow {  // hypotheses.tsv
  int64_t step = 0;
  Time stamp{};
  int64_t id = 0;
  FrameId frame = kNoFrame;
  HypothesisState state = HypothesisState::kJuvenile;
  bool dominant = false;
  int steps = 0;
  double q = 0.0;
  int observations = 0, matched = 0;
  bool bootstrapped = false;
  UncertainPose pose;
};

class RecordingSink final : public StepSink {
 public:
  void OnPose(Time stamp, const DominantOutput& d, PoseSource source) override {
    if (source != PoseSource::kScan || !d.valid) return;
    trajectory.push_back({stamp, d.frame, d.pose.mean, 0});
  }
  void OnStep(Time stamp, const Atlas& atlas) override {
    const StepStats& s = atlas.LastStats();
    TimingRow row;
    row.step = s.step;
    row.stamp = stamp;
    row.frames = atlas.Graph().FrameCount();
    row.hypotheses = s.hypotheses_alive;
    row.dominant = s.dominant_frame;
    timing.push_back(row);
    match_accepted += s.match_accepted;
    match_rejected += s.match_rejected;
    match_ambiguous += s.match_ambiguous;
    match_by_points += s.match_by_points;
    rejected_input += s.rejected_input;
    for (int r = 0; r < kMapMatchReasonCount; ++r) match_reasons[r] += s.match_reasons[r];
    seeded += s.seeded;
    matured += s.matured;
    deleted += s.deleted;
    killed_by_w += s.killed_by_w;
    refine_rejected += s.refine_rejected;
    contradicting += s.contradicting;
    if (!record_hypotheses) return;
    for (const Hypothesis& h : atlas.Hypotheses())
      hypotheses.push_back({s.step, stamp, h.id, h.frame, h.state, h.dominant, h.steps, h.q,
                            h.last_update.observations, h.last_update.matched, h.bootstrapped,
                            atlas.PoseOf(h)});
  }
  bool record_hypotheses = false;         // hypotheses.tsv asked for
  std::vector<HypothesisRow> hypotheses;  // its rows, formatted after the run
  std::vector<formats::FramePoseRow> trajectory;
  std::vector<TimingRow> timing;
  int64_t match_accepted = 0, match_rejected = 0, match_ambiguous = 0, match_by_points = 0;
  int64_t rejected_input = 0;
  std::array<int64_t, kMapMatchReasonCount> match_reasons{};
  int64_t seeded = 0, matured = 0, deleted = 0, killed_by_w = 0;
  int64_t refine_rejected = 0, contradicting = 0;
};

void Append(std::string& s, const char* fmt, auto... args) { formats::AppendF(&s, fmt, args...); }

// Resident set size now (kB), from /proc/self/statm; 0 where unavailable.
int64_t CurrentRssKb() {
  FILE* f = std::fopen("/proc/self/statm", "r");
  if (f == nullptr) return 0;
  long long size = 0, resident = 0;
  const int n = std::fscanf(f, "%lld %lld", &size, &resident);
  std::fclose(f);
  return n == 2 ? resident * (sysconf(_SC_PAGESIZE) / 1024) : 0;
}

double Median(std::vector<int64_t> v) {
  if (v.empty()) return 0.0;
  std::nth_element(v.begin(), v.begin() + static_cast<long>(v.size() / 2), v.end());
  return static_cast<double>(v[v.size() / 2]);
}

int64_t MaxRssKb() {
  rusage u{};
  return getrusage(RUSAGE_SELF, &u) == 0 ? static_cast<int64_t>(u.ru_maxrss) : 0;
}

// The reference pose within 1 ms of `stamp`, if any; `reference` sorted by stamp.
const Pose2* ReferenceAt(const std::vector<TruthSample>& reference, Time stamp) {
  const auto it =
      std::lower_bound(reference.begin(), reference.end(), stamp - std::chrono::milliseconds(1),
                       [](const TruthSample& s, Time t) { return s.stamp < t; });
  if (it == reference.end() || it->stamp > stamp + std::chrono::milliseconds(1)) return nullptr;
  return &it->pose;
}

// ReplayOptions::restart_after_scans: where the run is, the edges already looked at.
struct RestartWatch {
  int edges_seen = 0;
};

// After `scans` scans: the restart when it is due, then the first edge that joins the new part
// (frames >= restart_frame) to the old frames (ReplaySummary's restart fields).
void RestartOrWatchRejoin(const ReplayOptions& options, int64_t scans, Atlas* atlas,
                          ReplaySummary* sum, RestartWatch* watch) {
  if (options.restart_after_scans == 0) return;
  if (scans == options.restart_after_scans) {
    const bool read = atlas->Deserialize(atlas->Serialize());
    assert(read);
    (void)read;
    sum->restart_frame = static_cast<int>(atlas->ResumeInNewFrame());
    watch->edges_seen = atlas->Graph().EdgeCount();
    return;
  }
  if (sum->restart_frame < 0 || sum->rejoined_after_scans >= 0) return;
  const AtlasGraph& graph = atlas->Graph();
  for (; watch->edges_seen < graph.EdgeCount(); ++watch->edges_seen) {
    const AtlasEdge& e = graph.Edge(watch->edges_seen);
    if ((e.a < sum->restart_frame) != (e.b < sum->restart_frame)) {
      sum->rejoined_after_scans = scans - options.restart_after_scans;
      return;
    }
  }
}

}  // namespace

int64_t ThreadCpuNs() {
  timespec ts{};
  clock_gettime(CLOCK_THREAD_CPUTIME_ID, &ts);
  return static_cast<int64_t>(ts.tv_sec) * 1000000000 + ts.tv_nsec;
}

std::string CreateOutputDir(const std::string& dir) {
  if (mkdir(dir.c_str(), 0755) != 0 && errno != EEXIST)
    return "cannot create " + dir + ": " + std::strerror(errno);
  return "";
}

std::string WriteOutputFile(const std::string& dir, const char* name, const std::string& text) {
  return formats::WriteTextFile(dir + "/" + name, text);
}

std::vector<TruthSample> ReferenceAtScans(const carmen::CarmenLog& log) {
  std::vector<TruthSample> out;
  for (const carmen::ReferencePose& r : log.reference)
    if (r.at_laser) out.push_back(r.truth);
  std::stable_sort(out.begin(), out.end(),
                   [](const TruthSample& a, const TruthSample& b) { return a.stamp < b.stamp; });
  return out;
}

std::string ReplayOptions::Validate() const {
  if (std::string e = ValidateMapperSettings(mapper); !e.empty()) return "mapper: " + e;
  if (std::string e = loop.Validate(); !e.empty()) return "step loop: " + e;
  if (std::string e = closures.Validate(); !e.empty()) return "closure check: " + e;
  if (max_scans < 0) return "max_scans must be >= 0";
  if (restart_after_scans < 0) return "restart_after_scans must be >= 0";
  if (!(laser_max_range >= 0.0) || !std::isfinite(laser_max_range))
    return "laser_max_range must be >= 0 (0: each scan's own maximum)";
  return "";
}

ReplayResult RunReplay(const std::vector<carmen::CarmenEvent>& events, const ReplayOptions& options,
                       const std::string& out_dir,
                       const std::function<void(int64_t, int64_t)>& progress,
                       int64_t progress_every, const std::vector<TruthSample>& reference) {
  std::vector<SensorEvent> sensor_events;
  sensor_events.reserve(events.size());
  for (const carmen::CarmenEvent& e : events) sensor_events.push_back(e.event);
  return RunReplay(sensor_events, options, out_dir, progress, progress_every, reference);
}

ReplayResult RunReplay(const std::vector<SensorEvent>& events, const ReplayOptions& options,
                       const std::string& out_dir,
                       const std::function<void(int64_t, int64_t)>& progress,
                       int64_t progress_every, const std::vector<TruthSample>& reference) {
  ReplayResult result;
  if (std::string e = options.Validate(); !e.empty()) {
    result.error = "options: " + e;
    return result;
  }
  if (std::string e = CreateOutputDir(out_dir); !e.empty()) {
    result.error = e;
    return result;
  }
  // The items the maps use (live, atlasd steps these and no others).
  const bool use_scans = options.mapper.sensors != RangeSensors::kSonar;
  const bool use_sonar = options.mapper.sensors != RangeSensors::kLaser;
  int64_t total_scans = 0;
  for (const SensorEvent& e : events)
    if (use_scans && std::holds_alternative<LaserScan>(e)) ++total_scans;
  if (options.max_scans > 0) total_scans = std::min(total_scans, options.max_scans);

  std::unique_ptr<Atlas> atlas = MakeAtlas(options.mapper);
  StepLoopOptions loop_options = options.loop;
  StepLoop loop(loop_options, options.mapper, atlas.get());
  RecordingSink sink;
  sink.record_hypotheses = options.hypotheses;
  ReplaySummary& sum = result.summary;
  sink.trajectory.reserve(static_cast<size_t>(total_scans));
  sink.timing.reserve(static_cast<size_t>(total_scans));
  std::vector<int64_t> step_ns, step_cpu_ns;
  step_ns.reserve(static_cast<size_t>(total_scans));
  step_cpu_ns.reserve(static_cast<size_t>(total_scans));
  Time first_scan{}, last_scan{};
  RestartWatch restart;
  sum.rss_kb_before_steps = CurrentRssKb();
  for (const SensorEvent& e : events) {
    // Scans only: stop after the last one (the odometry after it moves nothing).
    if (!use_sonar ? sum.scans >= total_scans
                   : options.max_scans > 0 && sum.scans >= options.max_scans)
      break;
    if (const auto* o = std::get_if<OdometrySample>(&e)) {
      loop.AddOdometry(*o);
      ++sum.odometry_samples;
      continue;
    }
    const auto* scan = std::get_if<LaserScan>(&e);
    const auto* sonar = std::get_if<SonarReading>(&e);
    if (scan != nullptr && use_scans) {
      if (sum.scans == 0) first_scan = scan->stamp;
      last_scan = scan->stamp;
      LaserScan added(*scan);
      if (options.laser_max_range > 0.0)
        LimitLaserRange(&added, static_cast<float>(options.laser_max_range));
      loop.AddScan(std::move(added));
      ++sum.scans;
    } else if (sonar != nullptr && use_sonar) {
      loop.AddSonar(SonarReading(*sonar));
      ++sum.sonar_readings;
    } else {
      continue;
    }
    const size_t rows_before = sink.timing.size();
    const int64_t c0 = ThreadCpuNs();
    const auto t0 = std::chrono::steady_clock::now();
    loop.StepOne(&sink);
    const auto t1 = std::chrono::steady_clock::now();
    step_cpu_ns.push_back(ThreadCpuNs() - c0);
    const int64_t ns = std::chrono::duration_cast<std::chrono::nanoseconds>(t1 - t0).count();
    if (sink.timing.size() > rows_before) sink.timing.back().step_ns = ns;
    step_ns.push_back(ns);
    if (scan != nullptr && progress && progress_every > 0 && sum.scans % progress_every == 0)
      progress(sum.scans, total_scans);
    if (scan != nullptr) RestartOrWatchRejoin(options, sum.scans, atlas.get(), &sum, &restart);
  }
  sum.rss_kb_after_steps = CurrentRssKb();
  sum.step_budget_ms = std::chrono::duration<double, std::milli>(options.loop.step_budget).count();
  for (int64_t ns : step_ns) {
    if (static_cast<double>(ns) > sum.step_budget_ms * 1e6) ++sum.overruns;
  }
  for (int64_t ns : step_ns) sum.wall_seconds += static_cast<double>(ns) * 1e-9;
  if (!step_ns.empty()) {
    sum.step_ns_median = Median(step_ns);
    sum.step_ns_max = static_cast<double>(*std::max_element(step_ns.begin(), step_ns.end()));
    sum.step_cpu_ns_median = Median(step_cpu_ns);
    sum.step_cpu_ns_max =
        static_cast<double>(*std::max_element(step_cpu_ns.begin(), step_cpu_ns.end()));
  }
  sum.data_seconds = sum.scans > 0 ? ToSeconds(last_scan - first_scan) : 0.0;
  sum.scans_without_odometry = loop.scans_without_odometry();
  sum.scan_matches = loop.scan_matches();
  sum.scan_match_fallbacks = loop.scan_match_fallbacks();
  sum.match_accepted = sink.match_accepted;
  sum.match_rejected = sink.match_rejected;
  sum.match_ambiguous = sink.match_ambiguous;
  sum.match_by_points = sink.match_by_points;
  sum.rejected_input = sink.rejected_input;
  sum.match_reasons = sink.match_reasons;
  sum.seeded = sink.seeded;
  sum.matured = sink.matured;
  sum.deleted = sink.deleted;
  sum.killed_by_w = sink.killed_by_w;
  sum.refine_rejected = sink.refine_rejected;
  sum.contradicting = sink.contradicting;

  const AtlasGraph& graph = atlas->Graph();
  sum.frames = graph.FrameCount();
  sum.edges = graph.EdgeCount();

  std::string text = formats::FormatTrajectoryTsv(
      sink.trajectory, "atlas-replay trajectory: timestamp frame x y theta");
  if (std::string e = WriteOutputFile(out_dir, "trajectory.tsv", text); !e.empty()) {
    result.error = e;
    return result;
  }

  text = "# atlas-replay graph: from to x y theta c00 c01 c02 c11 c12 c22 kind\n";
  for (const AtlasEdge& edge : graph.Edges()) {
    switch (edge.kind) {
      case EdgeKind::kGenesis:
        ++sum.genesis_edges;
        break;
      case EdgeKind::kMapMatch:
        ++sum.map_match_edges;
        break;
      case EdgeKind::kRefined:
        ++sum.refined_edges;
        break;
    }
    if (edge.origin == EdgeKind::kMapMatch) ++sum.map_match_origin_edges;
    text += formats::GraphTsvRow(edge);
  }
  if (std::string e = WriteOutputFile(out_dir, "graph.tsv", text); !e.empty()) {
    result.error = e;
    return result;
  }

  text = "# atlas-replay timing: step timestamp frames hypotheses dominant step_ns\n";
  for (const TimingRow& r : sink.timing)
    Append(text, "%lld\t%.6f\t%d\t%d\t%d\t%lld\n", static_cast<long long>(r.step),
           ToSeconds(r.stamp), r.frames, r.hypotheses, r.dominant,
           static_cast<long long>(r.step_ns));
  if (std::string e = WriteOutputFile(out_dir, "timing.tsv", text); !e.empty()) {
    result.error = e;
    return result;
  }
  if (options.hypotheses) {
    text =
        "# atlas-replay hypotheses: step timestamp id frame state dominant steps q observations "
        "matched bootstrapped x y theta sx sy stheta\n";
    for (const HypothesisRow& h : sink.hypotheses) {
      const UncertainPose& p = h.pose;
      Append(text,
             "%lld\t%.6f\t%lld\t%d\t%s\t%d\t%d\t%.4f\t%d\t%d\t%d\t%.6f\t%.6f\t%.6f\t%.6f\t%.6f\t"
             "%.6f\n",
             static_cast<long long>(h.step), ToSeconds(h.stamp), static_cast<long long>(h.id),
             h.frame, HypothesisStateName(h.state), h.dominant ? 1 : 0, h.steps, h.q,
             h.observations, h.matched, h.bootstrapped ? 1 : 0, p.mean.x, p.mean.y, p.mean.theta,
             std::sqrt(p.cov(0, 0)), std::sqrt(p.cov(1, 1)), std::sqrt(p.cov(2, 2)));
    }
    if (std::string e = WriteOutputFile(out_dir, "hypotheses.tsv", text); !e.empty()) {
      result.error = e;
      return result;
    }
  }
  text = "# atlas-replay step_cpu: step cpu_ns (the stepping thread's CPU time per step)\n";
  for (size_t k = 0; k < sink.timing.size() && k < step_cpu_ns.size(); ++k)
    Append(text, "%lld\t%lld\n", static_cast<long long>(sink.timing[k].step),
           static_cast<long long>(step_cpu_ns[k]));
  if (std::string e = WriteOutputFile(out_dir, "step_cpu.tsv", text); !e.empty()) {
    result.error = e;
    return result;
  }

  text = formats::FormatGlobalTrajectory(
      sink.trajectory, formats::FramePosesFromFrameZero(graph),
      "atlas-replay global: timestamp x y theta (Dijkstra projection "
      "from frame 0)",
      &sum.global_rows);
  if (std::string e = WriteOutputFile(out_dir, "global.tsv", text); !e.empty()) {
    result.error = e;
    return result;
  }

  // frames.tsv: Genesis step (frame 0: step 1), its scan's stamp, the parent frame.
  std::vector<Time> stamp_of_step;  // by step - 1
  stamp_of_step.reserve(sink.timing.size());
  for (const TimingRow& r : sink.timing) {
    if (r.step != static_cast<int64_t>(stamp_of_step.size()) + 1) break;
    stamp_of_step.push_back(r.stamp);
  }
  std::vector<FrameId> parent(static_cast<size_t>(sum.frames), kNoFrame);
  for (const AtlasEdge& edge : graph.Edges())
    if (edge.origin == EdgeKind::kGenesis) parent[static_cast<size_t>(edge.b)] = edge.a;
  std::vector<std::optional<Pose2>> origin_reference(static_cast<size_t>(sum.frames));
  text = "# atlas-replay frames: frame step timestamp parent\n";
  for (FrameId f = 0; f < sum.frames; ++f) {
    const int64_t step = graph.Frame(f).created_step;
    const bool known = step >= 1 && step <= static_cast<int64_t>(stamp_of_step.size());
    const Time stamp = known ? stamp_of_step[static_cast<size_t>(step - 1)] : Time{};
    Append(text, "%d\t%lld\t%.6f\t%d\n", f, static_cast<long long>(step),
           known ? ToSeconds(stamp) : -1.0, parent[static_cast<size_t>(f)]);
    if (known && !reference.empty()) {
      const Pose2* ref = ReferenceAt(reference, stamp);
      if (ref != nullptr) origin_reference[static_cast<size_t>(f)] = *ref;
    }
  }
  if (std::string e = WriteOutputFile(out_dir, "frames.tsv", text); !e.empty()) {
    result.error = e;
    return result;
  }

  text = "# atlas-replay maps: frame line rho alpha x1 y1 x2 y2 c_rr c_ra c_aa\n";
  text += formats::MapsTsvRows(graph);
  if (std::string e = WriteOutputFile(out_dir, "maps.tsv", text); !e.empty()) {
    result.error = e;
    return result;
  }
  text =
      "# atlas-replay points: frame x y (cell centres of the laser points each frame keeps, or "
      "of a grid frame's occupied cells)\n";
  text += formats::PointsTsvRows(graph);
  if (std::string e = WriteOutputFile(out_dir, "points.tsv", text); !e.empty()) {
    result.error = e;
    return result;
  }

  if (!reference.empty()) {
    text = "# atlas-replay reference: timestamp x y theta (reference pose at each stepped scan)\n";
    for (const TimingRow& r : sink.timing) {
      const Pose2* ref = ReferenceAt(reference, r.stamp);
      if (ref == nullptr) continue;
      Append(text, "%.6f\t%.6f\t%.6f\t%.6f\n", ToSeconds(r.stamp), ref->x, ref->y, ref->theta);
      ++sum.reference_rows;
    }
    if (std::string e = WriteOutputFile(out_dir, "reference.tsv", text); !e.empty()) {
      result.error = e;
      return result;
    }
    const ClosureReport closures = CheckClosures(graph, origin_reference, options.closures);
    sum.closures_checked = static_cast<int>(closures.edges.size());
    sum.false_closures_chi2 = closures.false_chi2;
    sum.false_closures_axis = closures.false_axis;
    sum.gross_closures = closures.gross;
    if (std::string e = WriteOutputFile(out_dir, "closures.tsv", FormatClosures(closures));
        !e.empty()) {
      result.error = e;
      return result;
    }
  }

  if (options.refine) {
    const std::vector<std::optional<Pose2>> refined = options.refine(graph, &sum);
    text = formats::FormatGlobalTrajectory(sink.trajectory, refined,
                                           "atlas-replay global_refined: timestamp x y theta "
                                           "(global least-squares arrangement of the frames, "
                                           "frame 0 fixed)",
                                           &sum.refined_rows);
    if (std::string e = WriteOutputFile(out_dir, "global_refined.tsv", text); !e.empty()) {
      result.error = e;
      return result;
    }
  }
  sum.atlas_image_bytes = static_cast<int64_t>(atlas->Serialize().size());
  sum.max_rss_kb = MaxRssKb();
  if (std::string e = WriteOutputFile(out_dir, "summary.json", SummaryJson(sum)); !e.empty()) {
    result.error = e;
    return result;
  }
  result.trajectory = std::move(sink.trajectory);
  return result;
}

std::string SummaryJson(const ReplaySummary& s) {
  std::string t = "{";
  Append(t, "\"scans\": %lld, \"odometry_samples\": %lld, \"scans_without_odometry\": %lld, ",
         static_cast<long long>(s.scans), static_cast<long long>(s.odometry_samples),
         static_cast<long long>(s.scans_without_odometry));
  if (s.sonar_readings > 0)
    Append(t, "\"sonar_readings\": %lld, ", static_cast<long long>(s.sonar_readings));
  Append(t, "\"scan_matches\": %lld, \"scan_match_fallbacks\": %lld, ",
         static_cast<long long>(s.scan_matches), static_cast<long long>(s.scan_match_fallbacks));
  Append(t, "\"frames\": %d, \"edges\": %d, \"genesis_edges\": %d, \"map_match_edges\": %d, ",
         s.frames, s.edges, s.genesis_edges, s.map_match_edges);
  Append(t, "\"refined_edges\": %d, \"map_match_origin_edges\": %d, ", s.refined_edges,
         s.map_match_origin_edges);
  Append(t, "\"match_accepted\": %lld, \"match_rejected\": %lld, \"match_ambiguous\": %lld, ",
         static_cast<long long>(s.match_accepted), static_cast<long long>(s.match_rejected),
         static_cast<long long>(s.match_ambiguous));
  Append(t, "\"match_by_points\": %lld, ", static_cast<long long>(s.match_by_points));
  Append(t, "\"rejected_input\": %lld, ", static_cast<long long>(s.rejected_input));
  t += "\"match_reasons\": {";
  for (int r = 0; r < kMapMatchReasonCount; ++r)
    Append(t, "%s\"%s\": %lld", r > 0 ? ", " : "",
           MapMatchReasonName(static_cast<MapMatchReason>(r)),
           static_cast<long long>(s.match_reasons[r]));
  t += "}, ";
  Append(t, "\"seeded\": %lld, \"matured\": %lld, \"deleted\": %lld, \"killed_by_w\": %lld, ",
         static_cast<long long>(s.seeded), static_cast<long long>(s.matured),
         static_cast<long long>(s.deleted), static_cast<long long>(s.killed_by_w));
  Append(t, "\"refine_rejected\": %lld, \"contradicting\": %lld, ",
         static_cast<long long>(s.refine_rejected), static_cast<long long>(s.contradicting));
  Append(t, "\"global_rows\": %d, \"data_seconds\": %.6f, \"wall_seconds\": %.6f, ", s.global_rows,
         s.data_seconds, s.wall_seconds);
  Append(t, "\"speedup\": %.3f, \"step_ns_median\": %.0f, \"step_ns_max\": %.0f, ",
         s.wall_seconds > 0 ? s.data_seconds / s.wall_seconds : 0.0, s.step_ns_median,
         s.step_ns_max);
  Append(t, "\"step_budget_ms\": %.3f, \"overruns\": %lld, ", s.step_budget_ms,
         static_cast<long long>(s.overruns));
  Append(t, "\"step_cpu_ns_median\": %.0f, \"step_cpu_ns_max\": %.0f, ", s.step_cpu_ns_median,
         s.step_cpu_ns_max);
  Append(t, "\"atlas_image_bytes\": %lld, ", static_cast<long long>(s.atlas_image_bytes));
  if (s.restart_frame >= 0)
    Append(t, "\"restart_frame\": %d, \"rejoined_after_scans\": %lld, ", s.restart_frame,
           static_cast<long long>(s.rejoined_after_scans));
  Append(t, "\"max_rss_kb\": %lld, \"rss_kb_before_steps\": %lld, \"rss_kb_after_steps\": %lld",
         static_cast<long long>(s.max_rss_kb), static_cast<long long>(s.rss_kb_before_steps),
         static_cast<long long>(s.rss_kb_after_steps));
  if (s.closures_checked >= 0) {
    Append(t,
           ", \"reference_rows\": %d, \"closures_checked\": %d, \"false_closures_chi2\": %d, "
           "\"false_closures_axis\": %d, \"gross_closures\": %d",
           s.reference_rows, s.closures_checked, s.false_closures_chi2, s.false_closures_axis,
           s.gross_closures);
  }
  if (!s.refine_status.empty()) {
    Append(t,
           ", \"refine_status\": \"%s\", \"refined_frames\": %d, \"refine_constraints\": %d, "
           "\"refined_rows\": %d, \"refine_initial_cost\": %.6g, \"refine_final_cost\": %.6g, "
           "\"refine_seconds\": %.3f, \"refine_iterations\": %d, \"refine_unreached_frames\": %d, "
           "\"refine_skipped_edges\": %d",
           s.refine_status.c_str(), s.refined_frames, s.refine_constraints, s.refined_rows,
           s.refine_initial_cost, s.refine_final_cost, s.refine_seconds, s.refine_iterations,
           s.refine_unreached_frames, s.refine_skipped_edges);
  }
  t += "}\n";
  return t;
}

std::string SummaryText(const ReplaySummary& s) {
  std::string t;
  Append(t, "scans stepped        %lld (odometry samples %lld, scans without odometry %lld)\n",
         static_cast<long long>(s.scans), static_cast<long long>(s.odometry_samples),
         static_cast<long long>(s.scans_without_odometry));
  if (s.sonar_readings > 0)
    Append(t, "sonar readings       %lld stepped\n", static_cast<long long>(s.sonar_readings));
  if (s.scan_matches + s.scan_match_fallbacks > 0)
    Append(t, "scan matching        %lld increments matched, %lld fell back to the odometry\n",
           static_cast<long long>(s.scan_matches), static_cast<long long>(s.scan_match_fallbacks));
  if (s.rejected_input > 0)
    Append(t,
           "input refused        %lld steps (odometry, its covariance or the laser mounting not "
           "finite, or a jump of more than %.0f m): nothing was updated\n",
           static_cast<long long>(s.rejected_input), kMaxStepTranslation);
  Append(t, "frames               %d\n", s.frames);
  Append(t,
         "edges                %d (now: genesis %d, map-match %d, refined %d; made by "
         "map-matching %d)\n",
         s.edges, s.genesis_edges, s.map_match_edges, s.refined_edges, s.map_match_origin_edges);
  Append(t,
         "map-match outcomes   accepted %lld (the frames' points chose %lld), rejected %lld, "
         "ambiguous %lld\n",
         static_cast<long long>(s.match_accepted), static_cast<long long>(s.match_by_points),
         static_cast<long long>(s.match_rejected), static_cast<long long>(s.match_ambiguous));
  t += "  by reason         ";
  for (int r = 0; r < kMapMatchReasonCount; ++r)
    Append(t, "%s%s %lld", r > 0 ? ", " : " ", MapMatchReasonName(static_cast<MapMatchReason>(r)),
           static_cast<long long>(s.match_reasons[r]));
  t += "\n";
  Append(t, "traversal            seeded %lld, matured %lld, deleted %lld (w failed %lld)\n",
         static_cast<long long>(s.seeded), static_cast<long long>(s.matured),
         static_cast<long long>(s.deleted), static_cast<long long>(s.killed_by_w));
  Append(t,
         "consistency          refinements rejected by the gate %lld, hypotheses retired "
         "for contradicting the dominant %lld\n",
         static_cast<long long>(s.refine_rejected), static_cast<long long>(s.contradicting));
  Append(t, "global rows          %d\n", s.global_rows);
  Append(t, "data time            %.3f s\n", s.data_seconds);
  Append(t, "stepping wall time   %.3f s (%.1fx real time)\n", s.wall_seconds,
         s.wall_seconds > 0 ? s.data_seconds / s.wall_seconds : 0.0);
  Append(t, "step time            median %.1f us, max %.1f us (budget %.1f ms, %lld over)\n",
         s.step_ns_median * 1e-3, s.step_ns_max * 1e-3, s.step_budget_ms,
         static_cast<long long>(s.overruns));
  Append(t, "step CPU time        median %.1f us, max %.1f us (the stepping thread's own time)\n",
         s.step_cpu_ns_median * 1e-3, s.step_cpu_ns_max * 1e-3);
  Append(t,
         "memory               max RSS %lld kB; RSS %lld kB before the first step, %lld kB after "
         "the last\n",
         static_cast<long long>(s.max_rss_kb), static_cast<long long>(s.rss_kb_before_steps),
         static_cast<long long>(s.rss_kb_after_steps));
  Append(t, "atlas state          %lld bytes serialised (%.1f kB per frame)\n",
         static_cast<long long>(s.atlas_image_bytes),
         s.frames > 0 ? static_cast<double>(s.atlas_image_bytes) / 1024.0 / s.frames : 0.0);
  if (s.closures_checked >= 0) {
    Append(t,
           "closures             %d map-match edges checked against the reference: %d false "
           "(chi2 3 dof > 14.16), %d beyond 3 sigma on an axis, %d gross (> 0.5 m or 5 deg)\n",
           s.closures_checked, s.false_closures_chi2, s.false_closures_axis, s.gross_closures);
  }
  if (!s.refine_status.empty()) {
    Append(t,
           "refinement           %s: %d frames, %d constraints, cost %.6g -> %.6g, %d "
           "iterations, %.3f s, %d rows; left out: %d frames not connected to frame 0, %d edges "
           "with unusable covariance\n",
           s.refine_status.c_str(), s.refined_frames, s.refine_constraints, s.refine_initial_cost,
           s.refine_final_cost, s.refine_iterations, s.refine_seconds, s.refined_rows,
           s.refine_unreached_frames, s.refine_skipped_edges);
  }
  return t;
}

}  // namespace atlas::replay
