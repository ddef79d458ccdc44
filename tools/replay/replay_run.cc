#include "tools/replay/replay_run.h"

#include <sys/stat.h>

#include <algorithm>
#include <cerrno>
#include <chrono>
#include <cstdio>
#include <cstring>
#include <memory>

#include "core/atlas/dijkstra_projection.h"

namespace atlas::replay {
namespace {

struct TrajectoryRow {
  Time stamp{};
  FrameId frame = kNoFrame;
  Pose2 pose;
};

struct TimingRow {
  int64_t step = 0;
  Time stamp{};
  int frames = 0;
  int hypotheses = 0;
  FrameId dominant = kNoFrame;
  int64_t step_ns = 0;
};

class RecordingSink final : public StepSink {
 public:
  void OnPose(Time stamp, const DominantOutput& d, PoseSource source) override {
    if (source != PoseSource::kScan || !d.valid) return;
    trajectory.push_back({stamp, d.frame, d.pose.mean});
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
  }
  std::vector<TrajectoryRow> trajectory;
  std::vector<TimingRow> timing;
  int64_t match_accepted = 0, match_rejected = 0, match_ambiguous = 0;
};

struct OutFile {
  FILE* f = nullptr;
  ~OutFile() {
    if (f != nullptr) std::fclose(f);
  }
};

// Writes `text` to dir/name; returns an error message or "".
std::string WriteFile(const std::string& dir, const char* name, const std::string& text) {
  const std::string path = dir + "/" + name;
  OutFile out;
  out.f = std::fopen(path.c_str(), "w");
  if (out.f == nullptr) return "cannot write " + path + ": " + std::strerror(errno);
  if (std::fwrite(text.data(), 1, text.size(), out.f) != text.size())
    return "cannot write " + path + ": " + std::strerror(errno);
  const int rc = std::fclose(out.f);
  out.f = nullptr;
  if (rc != 0) return "cannot write " + path + ": " + std::strerror(errno);
  return "";
}

void Append(std::string& s, const char* fmt, auto... args) {
  char buf[512];
  const int n = std::snprintf(buf, sizeof buf, fmt, args...);
  s.append(buf, static_cast<size_t>(std::clamp(n, 0, static_cast<int>(sizeof buf) - 1)));
}

}  // namespace

std::string ReplayOptions::Validate() const {
  if (std::string e = ValidateMapperSettings(mapper); !e.empty()) return "mapper: " + e;
  if (std::string e = loop.Validate(); !e.empty()) return "step loop: " + e;
  if (max_scans < 0) return "max_scans must be >= 0";
  return "";
}

ReplayResult RunReplay(const std::vector<carmen::CarmenEvent>& events, const ReplayOptions& options,
                       const std::string& out_dir,
                       const std::function<void(int64_t, int64_t)>& progress,
                       int64_t progress_every) {
  ReplayResult result;
  if (std::string e = options.Validate(); !e.empty()) {
    result.error = "options: " + e;
    return result;
  }
  if (mkdir(out_dir.c_str(), 0755) != 0 && errno != EEXIST) {
    result.error = "cannot create " + out_dir + ": " + std::strerror(errno);
    return result;
  }
  int64_t total_scans = 0;
  for (const carmen::CarmenEvent& e : events)
    if (std::holds_alternative<LaserScan>(e.event)) ++total_scans;
  if (options.max_scans > 0) total_scans = std::min(total_scans, options.max_scans);

  std::unique_ptr<Atlas> atlas = MakeAtlas(options.mapper);
  StepLoopOptions loop_options = options.loop;
  StepLoop loop(loop_options, options.mapper, atlas.get());
  RecordingSink sink;
  ReplaySummary& sum = result.summary;
  sink.trajectory.reserve(static_cast<size_t>(total_scans));
  sink.timing.reserve(static_cast<size_t>(total_scans));
  std::vector<int64_t> step_ns;
  step_ns.reserve(static_cast<size_t>(total_scans));
  Time first_scan{}, last_scan{};
  for (const carmen::CarmenEvent& e : events) {
    if (sum.scans >= total_scans) break;
    if (const auto* o = std::get_if<OdometrySample>(&e.event)) {
      loop.AddOdometry(*o);
      ++sum.odometry_samples;
      continue;
    }
    const auto* scan = std::get_if<LaserScan>(&e.event);
    if (scan == nullptr) continue;
    if (sum.scans == 0) first_scan = scan->stamp;
    last_scan = scan->stamp;
    loop.AddScan(LaserScan(*scan));
    const size_t rows_before = sink.timing.size();
    const auto t0 = std::chrono::steady_clock::now();
    loop.StepOne(&sink);
    const auto t1 = std::chrono::steady_clock::now();
    const int64_t ns = std::chrono::duration_cast<std::chrono::nanoseconds>(t1 - t0).count();
    if (sink.timing.size() > rows_before) sink.timing.back().step_ns = ns;
    step_ns.push_back(ns);
    ++sum.scans;
    if (progress && progress_every > 0 && sum.scans % progress_every == 0)
      progress(sum.scans, total_scans);
  }
  for (int64_t ns : step_ns) sum.wall_seconds += static_cast<double>(ns) * 1e-9;
  if (!step_ns.empty()) {
    std::vector<int64_t> sorted = step_ns;
    std::nth_element(sorted.begin(), sorted.begin() + static_cast<long>(sorted.size() / 2),
                     sorted.end());
    sum.step_ns_median = static_cast<double>(sorted[sorted.size() / 2]);
    sum.step_ns_max = static_cast<double>(*std::max_element(step_ns.begin(), step_ns.end()));
  }
  sum.data_seconds = sum.scans > 0 ? ToSeconds(last_scan - first_scan) : 0.0;
  sum.scans_without_odometry = loop.scans_without_odometry();
  sum.match_accepted = sink.match_accepted;
  sum.match_rejected = sink.match_rejected;
  sum.match_ambiguous = sink.match_ambiguous;

  const AtlasGraph& graph = atlas->Graph();
  sum.frames = graph.FrameCount();
  sum.edges = graph.EdgeCount();

  std::string text = "# atlas-replay trajectory: timestamp frame x y theta\n";
  for (const TrajectoryRow& r : sink.trajectory)
    Append(text, "%.6f\t%d\t%.6f\t%.6f\t%.6f\n", ToSeconds(r.stamp), r.frame, r.pose.x, r.pose.y,
           r.pose.theta);
  if (std::string e = WriteFile(out_dir, "trajectory.tsv", text); !e.empty()) {
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
    const Pose2& p = edge.b_in_a.mean;
    const Mat3& c = edge.b_in_a.cov;
    Append(text, "%d\t%d\t%.6f\t%.6f\t%.6f\t%.9g\t%.9g\t%.9g\t%.9g\t%.9g\t%.9g\t%s\n", edge.a,
           edge.b, p.x, p.y, p.theta, c(0, 0), c(0, 1), c(0, 2), c(1, 1), c(1, 2), c(2, 2),
           EdgeKindName(edge.kind));
  }
  if (std::string e = WriteFile(out_dir, "graph.tsv", text); !e.empty()) {
    result.error = e;
    return result;
  }

  text = "# atlas-replay timing: step timestamp frames hypotheses dominant step_ns\n";
  for (const TimingRow& r : sink.timing)
    Append(text, "%lld\t%.6f\t%d\t%d\t%d\t%lld\n", static_cast<long long>(r.step),
           ToSeconds(r.stamp), r.frames, r.hypotheses, r.dominant,
           static_cast<long long>(r.step_ns));
  if (std::string e = WriteFile(out_dir, "timing.tsv", text); !e.empty()) {
    result.error = e;
    return result;
  }

  text = "# atlas-replay global: timestamp x y theta (Dijkstra projection from frame 0)\n";
  if (sum.frames > 0) {
    const Projection projection = DijkstraProjection(graph, 0);
    std::vector<const ProjectedFrame*> placed(static_cast<size_t>(sum.frames), nullptr);
    for (const ProjectedFrame& f : projection.entries) placed[static_cast<size_t>(f.frame)] = &f;
    for (const TrajectoryRow& r : sink.trajectory) {
      if (r.frame < 0 || r.frame >= sum.frames || placed[static_cast<size_t>(r.frame)] == nullptr)
        continue;
      const Pose2 g = Compose(placed[static_cast<size_t>(r.frame)]->pose.mean, r.pose);
      Append(text, "%.6f\t%.6f\t%.6f\t%.6f\n", ToSeconds(r.stamp), g.x, g.y, g.theta);
      ++sum.global_rows;
    }
  }
  if (std::string e = WriteFile(out_dir, "global.tsv", text); !e.empty()) {
    result.error = e;
    return result;
  }
  if (std::string e = WriteFile(out_dir, "summary.json", SummaryJson(sum)); !e.empty()) {
    result.error = e;
    return result;
  }
  return result;
}

std::string SummaryJson(const ReplaySummary& s) {
  std::string t = "{";
  Append(t, "\"scans\": %lld, \"odometry_samples\": %lld, \"scans_without_odometry\": %lld, ",
         static_cast<long long>(s.scans), static_cast<long long>(s.odometry_samples),
         static_cast<long long>(s.scans_without_odometry));
  Append(t, "\"frames\": %d, \"edges\": %d, \"genesis_edges\": %d, \"map_match_edges\": %d, ",
         s.frames, s.edges, s.genesis_edges, s.map_match_edges);
  Append(t, "\"refined_edges\": %d, \"map_match_origin_edges\": %d, ", s.refined_edges,
         s.map_match_origin_edges);
  Append(t, "\"match_accepted\": %lld, \"match_rejected\": %lld, \"match_ambiguous\": %lld, ",
         static_cast<long long>(s.match_accepted), static_cast<long long>(s.match_rejected),
         static_cast<long long>(s.match_ambiguous));
  Append(t, "\"global_rows\": %d, \"data_seconds\": %.6f, \"wall_seconds\": %.6f, ", s.global_rows,
         s.data_seconds, s.wall_seconds);
  Append(t, "\"speedup\": %.3f, \"step_ns_median\": %.0f, \"step_ns_max\": %.0f}\n",
         s.wall_seconds > 0 ? s.data_seconds / s.wall_seconds : 0.0, s.step_ns_median,
         s.step_ns_max);
  return t;
}

std::string SummaryText(const ReplaySummary& s) {
  std::string t;
  Append(t, "scans stepped        %lld (odometry samples %lld, scans without odometry %lld)\n",
         static_cast<long long>(s.scans), static_cast<long long>(s.odometry_samples),
         static_cast<long long>(s.scans_without_odometry));
  Append(t, "frames               %d\n", s.frames);
  Append(t,
         "edges                %d (now: genesis %d, map-match %d, refined %d; made by "
         "map-matching %d)\n",
         s.edges, s.genesis_edges, s.map_match_edges, s.refined_edges, s.map_match_origin_edges);
  Append(t, "map-match outcomes   accepted %lld, rejected %lld, ambiguous %lld\n",
         static_cast<long long>(s.match_accepted), static_cast<long long>(s.match_rejected),
         static_cast<long long>(s.match_ambiguous));
  Append(t, "global rows          %d\n", s.global_rows);
  Append(t, "data time            %.3f s\n", s.data_seconds);
  Append(t, "stepping wall time   %.3f s (%.1fx real time)\n", s.wall_seconds,
         s.wall_seconds > 0 ? s.data_seconds / s.wall_seconds : 0.0);
  Append(t, "step time            median %.1f us, max %.1f us\n", s.step_ns_median * 1e-3,
         s.step_ns_max * 1e-3);
  return t;
}

}  // namespace atlas::replay
