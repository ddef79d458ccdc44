#include "formats/replay_dir.h"

#include <algorithm>
#include <functional>

#include "core/atlas/dijkstra_projection.h"
#include "core/common/parse_number.h"
#include "formats/pose_file.h"
#include "formats/text_rows.h"

namespace atlas::formats {
namespace {

// Parses fields [first, first + n) as numbers into `v`; "" or what is wrong.
std::string Numbers(std::span<const std::string_view> f, size_t first, size_t n, double* v) {
  for (size_t k = 0; k < n; ++k)
    if (std::string e = NumberField(f[first + k], first + k + 1, &v[k]); !e.empty()) return e;
  return "";
}

// A pose file's rows into `out`.
std::string ParsePoses(std::string_view text, const std::string& source,
                       std::vector<eval::TimedPose>* out) {
  PoseRows rows = ParsePoseRows(text, source);
  *out = std::move(rows.poses);
  return rows.error;
}

}  // namespace

std::string ParseTimingRows(std::string_view text, const std::string& source,
                            std::vector<TimingRecord>* out) {
  return ForEachRow(
      text, source, 6, "step timestamp frames hypotheses dominant step_ns",
      [&](std::span<const std::string_view> f, int64_t) {
        TimingRecord r;
        int64_t frames = 0, hyps = 0;
        if (!ParseInteger(f[0], &r.step) || !ParseNumber(f[1], &r.stamp_s) ||
            !ParseInteger(f[2], &frames) || !ParseInteger(f[3], &hyps) || frames < 0 || hyps < 0 ||
            !ParseInteger(f[5], &r.step_ns))
          return std::string("expected: step timestamp frames hypotheses dominant step_ns");
        if (std::string e = FrameField(f[4], 5, true, &r.dominant); !e.empty()) return e;
        r.frames = static_cast<int>(std::min<int64_t>(frames, 100000000));
        r.hypotheses = static_cast<int>(std::min<int64_t>(hyps, 100000000));
        out->push_back(r);
        return std::string();
      });
}

std::string ParseFrameRows(std::string_view text, const std::string& source,
                           std::vector<FrameRecord>* out) {
  return ForEachRow(text, source, 4, "frame step timestamp parent",
                    [&](std::span<const std::string_view> f, int64_t) {
                      FrameRecord r;
                      if (std::string e = FrameField(f[0], 1, false, &r.frame); !e.empty())
                        return e;
                      if (!ParseInteger(f[1], &r.step) || !ParseNumber(f[2], &r.stamp_s))
                        return std::string("expected: frame step timestamp parent");
                      if (std::string e = FrameField(f[3], 4, true, &r.parent); !e.empty())
                        return e;
                      out->push_back(r);
                      return std::string();
                    });
}

std::string ParseMapRows(std::string_view text, const std::string& source,
                         std::vector<FrameLine>* out) {
  return ForEachRow(text, source, 11, "frame line rho alpha x1 y1 x2 y2 c_rr c_ra c_aa",
                    [&](std::span<const std::string_view> f, int64_t) {
                      FrameLine r;
                      if (std::string e = FrameField(f[0], 1, false, &r.frame); !e.empty())
                        return e;
                      int64_t id = 0;
                      if (!ParseInteger(f[1], &id)) return std::string("field 2 is not a line id");
                      double v[9];
                      if (std::string e = Numbers(f, 2, 9, v); !e.empty()) return e;
                      r.line.id = static_cast<int>(id);
                      r.line.rho = v[0];
                      r.line.alpha = v[1];
                      r.line.endpoint_a = Vec2(v[2], v[3]);
                      r.line.endpoint_b = Vec2(v[4], v[5]);
                      r.line.cov << v[6], v[7], v[7], v[8];
                      out->push_back(r);
                      return std::string();
                    });
}

std::string ParsePointRows(std::string_view text, const std::string& source,
                           std::vector<FramePointRow>* out) {
  return ForEachRow(text, source, 3, "frame x y",
                    [&](std::span<const std::string_view> f, int64_t) {
                      FramePointRow r;
                      if (std::string e = FrameField(f[0], 1, false, &r.frame); !e.empty())
                        return e;
                      double v[2];
                      if (std::string e = Numbers(f, 1, 2, v); !e.empty()) return e;
                      r.p = Vec2(v[0], v[1]);
                      out->push_back(r);
                      return std::string();
                    });
}

std::string ReadReplayOutput(const std::string& dir, const ReplayFilesWanted& wanted,
                             ReplayOutput* out) {
  *out = ReplayOutput{};
  struct Item {
    const char* name;
    bool required;
    std::function<std::string(std::string_view, const std::string&)> parse;
  };
  const Item items[] = {
      {"trajectory.tsv", wanted.trajectory,
       [&](auto t, auto& s) { return ParseTrajectoryTsv(t, s, &out->trajectory); }},
      {"graph.tsv", wanted.graph,
       [&](auto t, auto& s) { return ParseGraphTsv(t, s, &out->graph); }},
      {"timing.tsv", wanted.timing,
       [&](auto t, auto& s) { return ParseTimingRows(t, s, &out->timing); }},
      {"frames.tsv", wanted.frames,
       [&](auto t, auto& s) { return ParseFrameRows(t, s, &out->frames); }},
      {"maps.tsv", wanted.maps, [&](auto t, auto& s) { return ParseMapRows(t, s, &out->lines); }},
      {"points.tsv", false, [&](auto t, auto& s) { return ParsePointRows(t, s, &out->points); }},
      {"step_cpu.tsv", wanted.step_cpu,
       [&](auto t, auto& s) {
         return ForEachRow(
             t, s, 2, "step cpu_ns", [&](std::span<const std::string_view> f, int64_t) {
               int64_t step = 0, ns = 0;
               if (!ParseInteger(f[0], &step) || !ParseInteger(f[1], &ns) ||
                   step != static_cast<int64_t>(out->step_cpu_ns.size()) + 1)
                 return std::string("expected: step cpu_ns, steps counting up from 1");
               out->step_cpu_ns.push_back(ns);
               return std::string();
             });
       }},
      {"global.tsv", false, [&](auto t, auto& s) { return ParsePoses(t, s, &out->global); }},
      {"global_refined.tsv", false,
       [&](auto t, auto& s) { return ParsePoses(t, s, &out->refined); }},
  };
  std::vector<std::string> present;
  for (const Item& item : items) {
    const std::string path = dir + "/" + item.name;
    TextFile f = ReadTextFile(path);
    if (!f.error.empty()) {
      if (f.missing && !item.required) continue;
      return f.error + (f.missing ? " (is " + dir + " an atlas-replay output directory?)" : "");
    }
    if (std::string e = item.parse(f.text, path); !e.empty()) return e;
    present.push_back(item.name);
  }
  const auto has = [&](const char* name) {
    return std::find(present.begin(), present.end(), name) != present.end();
  };
  // A file that is there but holds no rows where a run always writes some.
  const auto empty = [&](const char* name, const std::string& why) {
    return dir + "/" + name + ": no rows (" + why + ")";
  };
  if (wanted.trajectory && out->trajectory.empty())
    return empty("trajectory.tsv", "atlas-replay writes one per stepped scan");
  if (wanted.timing && out->timing.empty())
    return empty("timing.tsv", "atlas-replay writes one per step");
  if (wanted.maps && out->lines.empty() && out->points.empty())
    return empty("maps.tsv",
                 "and points.tsv has none either: no frame holds a line or a point, "
                 "nothing to draw");
  if (wanted.step_cpu && out->step_cpu_ns.empty())
    return empty("step_cpu.tsv", "atlas-replay writes one per step");
  if (!out->trajectory.empty()) {
    if (has("global.tsv") && out->global.empty())
      return empty("global.tsv",
                   "trajectory.tsv has " + std::to_string(out->trajectory.size()) +
                       "; remove global.tsv to have it computed from trajectory.tsv and graph.tsv");
    if (has("global_refined.tsv") && out->refined.empty())
      return empty("global_refined.tsv", "trajectory.tsv has " +
                                             std::to_string(out->trajectory.size()) +
                                             "; re-run atlas-refine " + dir + " or remove it");
  }
  // How many frames the run made: frames.tsv has a row per frame, timing.tsv the count after
  // each step. An atlas exported from atlasd has neither: its frames are those named.
  int known = -1;
  std::string known_from;
  if (!out->frames.empty()) {
    for (const auto& r : out->frames) known = std::max(known, r.frame + 1);
    known_from = "frames.tsv";
  } else if (!out->timing.empty()) {
    for (const auto& r : out->timing) known = std::max(known, r.frames);
    known_from = "timing.tsv";
  }
  if (known >= 0) {
    const auto beyond = [&](const char* file, int64_t line, const std::string& what, FrameId f) {
      return dir + "/" + file + ":" + std::to_string(line) + ": " + what + " names frame " +
             std::to_string(f) + ", but the run has " + std::to_string(known) + " frames (0.." +
             std::to_string(known - 1) + ", " + known_from +
             "); the files are not from one run, or the row is damaged";
    };
    for (size_t i = 0; i < out->graph.edges.size(); ++i) {
      const eval::EdgeRow& e = out->graph.edges[i];
      if (std::max(e.from, e.to) >= known)
        return beyond("graph.tsv", out->graph.lines[i],
                      "edge " + std::to_string(e.from) + "-" + std::to_string(e.to),
                      std::max(e.from, e.to));
    }
    for (const FramePoseRow& r : out->trajectory)
      if (r.frame >= known) return beyond("trajectory.tsv", r.line, "the row", r.frame);
  }
  int n = 0;
  for (const auto& r : out->trajectory) n = std::max(n, r.frame + 1);
  n = std::max(n, out->graph.frame_count);
  for (const auto& r : out->timing) n = std::max({n, r.frames, r.dominant + 1});
  for (const auto& r : out->frames) n = std::max({n, r.frame + 1, r.parent + 1});
  for (const auto& r : out->lines) n = std::max(n, r.frame + 1);
  for (const auto& r : out->points) n = std::max(n, r.frame + 1);
  out->frame_count = n;
  if (has("graph.tsv") && out->graph.edges.empty() && n > 1)
    return empty("graph.tsv", "the run has " + std::to_string(n) +
                                  " frames, and every frame after frame 0 is joined by the "
                                  "Genesis edge that made it");
  return "";
}

std::vector<std::optional<Pose2>> FramePosesFrom(const AtlasGraph& graph, FrameId source) {
  std::vector<std::optional<Pose2>> pose(static_cast<size_t>(graph.FrameCount()));
  if (graph.HasFrame(source))
    for (const ProjectedFrame& f : DijkstraProjection(graph, source).entries)
      pose[static_cast<size_t>(f.frame)] = f.pose.mean;
  return pose;
}

std::vector<eval::TimedPose> PlaceTrajectory(const std::vector<FramePoseRow>& trajectory,
                                             const std::vector<std::optional<Pose2>>& frame_pose) {
  std::vector<eval::TimedPose> out;
  out.reserve(trajectory.size());
  for (const FramePoseRow& r : trajectory) {
    if (r.frame < 0 || static_cast<size_t>(r.frame) >= frame_pose.size() ||
        !frame_pose[static_cast<size_t>(r.frame)])
      continue;
    out.push_back({r.stamp, Compose(*frame_pose[static_cast<size_t>(r.frame)], r.pose)});
  }
  return out;
}

std::string FormatGlobalTrajectory(const std::vector<FramePoseRow>& trajectory,
                                   const std::vector<std::optional<Pose2>>& frame_pose,
                                   const std::string& comment, int* rows_written) {
  const std::vector<eval::TimedPose> rows = PlaceTrajectory(trajectory, frame_pose);
  if (rows_written != nullptr) *rows_written = static_cast<int>(rows.size());
  return FormatPoseRows(rows, comment);
}

std::string MapsTsvRows(const AtlasGraph& graph) {
  std::string text;
  for (FrameId f = 0; f < graph.FrameCount(); ++f) {
    const LocalMap* map = graph.Frame(f).map.get();
    if (map == nullptr) continue;
    for (const MapLine& l : map->Lines())
      AppendF(&text, "%d\t%d\t%.6f\t%.6f\t%.4f\t%.4f\t%.4f\t%.4f\t%.9g\t%.9g\t%.9g\n", f, l.id,
              l.rho, l.alpha, l.endpoint_a.x(), l.endpoint_a.y(), l.endpoint_b.x(),
              l.endpoint_b.y(), l.cov(0, 0), l.cov(0, 1), l.cov(1, 1));
  }
  return text;
}

std::string PointsTsvRows(const AtlasGraph& graph) {
  std::string text;
  for (FrameId f = 0; f < graph.FrameCount(); ++f) {
    const MapFrame& frame = graph.Frame(f);
    std::vector<Vec2> points = frame.points.Centres();
    if (points.empty() && frame.map != nullptr) points = frame.map->Points(kMaxMapPointsPerFrame);
    for (const Vec2& c : points) AppendF(&text, "%d\t%.2f\t%.2f\n", f, c.x(), c.y());
  }
  return text;
}

}  // namespace atlas::formats
