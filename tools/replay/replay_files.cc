#include "tools/replay/replay_files.h"

#include <zlib.h>

#include <algorithm>
#include <cerrno>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <functional>

#include "core/atlas/dijkstra_projection.h"
#include "core/common/parse_number.h"
#include "core/geometry/covariance.h"

namespace atlas::replay {
namespace {

// Calls `row(fields, where)` for every data line; stops at the first error it returns.
// `current_line` (optional) holds the number of the line being parsed while `row` runs.
std::string ForEachRow(std::string_view text, const std::string& source, size_t field_count,
                       const std::function<std::string(const std::vector<std::string_view>&)>& row,
                       int64_t* current_line = nullptr) {
  std::vector<std::string_view> fields;
  size_t pos = 0;
  int64_t line_no = 0;
  while (pos < text.size()) {
    size_t end = text.find('\n', pos);
    if (end == std::string_view::npos) end = text.size();
    std::string_view line = text.substr(pos, end - pos);
    pos = end + 1;
    ++line_no;
    if (!line.empty() && line.back() == '\r') line.remove_suffix(1);
    fields.clear();
    size_t i = 0;
    while (i < line.size()) {
      while (i < line.size() && (line[i] == ' ' || line[i] == '\t')) ++i;
      if (i >= line.size()) break;
      size_t j = i;
      while (j < line.size() && line[j] != ' ' && line[j] != '\t') ++j;
      fields.push_back(line.substr(i, j - i));
      i = j;
    }
    if (fields.empty() || fields[0][0] == '#') continue;
    const std::string where = source + ":" + std::to_string(line_no) + ": ";
    if (current_line != nullptr) *current_line = line_no;
    if (fields.size() != field_count)
      return where + "expected " + std::to_string(field_count) + " fields, found " +
             std::to_string(fields.size());
    if (std::string e = row(fields); !e.empty()) return where + e;
  }
  return "";
}

// Parses fields [first, first + n) as numbers into `v`; "" or what is wrong.
std::string Numbers(const std::vector<std::string_view>& f, size_t first, size_t n, double* v) {
  for (size_t k = 0; k < n; ++k)
    if (!ParseNumber(f[first + k], &v[k]))
      return "field " + std::to_string(first + k + 1) + " '" + std::string(f[first + k]) +
             "' is not a finite number";
  return "";
}

// Positions beyond 1e7 m (10,000 km) and angles beyond 1e3 rad are not from a run: reject them
// before they overflow a composition or an image transform.
std::string PoseRange(const double* v, size_t first_field) {
  for (int k = 0; k < 3; ++k) {
    const double limit = k < 2 ? 1e7 : 1e3;
    if (std::abs(v[k]) > limit)
      return "field " + std::to_string(first_field + k + 1) + " (" +
             (k < 2 ? "position" : "angle") + ") is out of range (|value| > " +
             (k < 2 ? "1e7 m" : "1e3 rad") + ")";
  }
  return "";
}

// Stamps are converted to integer nanoseconds: beyond 4e9 s they overflow.
std::string StampRange(double t, size_t field) {
  if (std::abs(t) > 4e9)
    return "field " + std::to_string(field + 1) + " (timestamp) is out of range (|t| > 4e9 s)";
  return "";
}

std::string FrameField(std::string_view s, size_t index, bool allow_none, FrameId* frame) {
  int64_t v = 0;
  if (!ParseInteger(s, &v) || v < (allow_none ? -1 : 0) || v > 100000000)
    return "field " + std::to_string(index + 1) + " '" + std::string(s) + "' is not a frame id";
  *frame = static_cast<FrameId>(v);
  return "";
}

struct FileText {
  std::string text;
  std::string error;
  bool missing = false;
};

FileText ReadFile(const std::string& path) {
  FileText out;
  gzFile f = gzopen(path.c_str(), "rb");
  if (f == nullptr) {
    out.missing = errno == ENOENT;
    out.error = path + ": cannot open: " + std::strerror(errno);
    return out;
  }
  char buf[1 << 16];
  int n = 0;
  while ((n = gzread(f, buf, sizeof buf)) > 0) out.text.append(buf, static_cast<size_t>(n));
  if (n < 0) out.error = path + ": read error";
  gzclose(f);
  return out;
}

}  // namespace

bool EdgeKindFromName(std::string_view name, EdgeKind* kind) {
  for (EdgeKind k : {EdgeKind::kGenesis, EdgeKind::kMapMatch, EdgeKind::kRefined}) {
    if (name == EdgeKindName(k)) {
      *kind = k;
      return true;
    }
  }
  return false;
}

std::string ParseTrajectoryRows(std::string_view text, const std::string& source,
                                std::vector<StampedFramePose>* out) {
  int64_t line = 0;
  return ForEachRow(
      text, source, 5,
      [&](const std::vector<std::string_view>& f) {
        StampedFramePose r;
        double v[3];
        if (!ParseNumber(f[0], &r.stamp_s)) return std::string("field 1 is not a timestamp");
        if (std::string e = StampRange(r.stamp_s, 0); !e.empty()) return e;
        if (std::string e = FrameField(f[1], 1, false, &r.frame); !e.empty()) return e;
        if (std::string e = Numbers(f, 2, 3, v); !e.empty()) return e;
        if (std::string e = PoseRange(v, 2); !e.empty()) return e;
        r.pose = Pose2{v[0], v[1], v[2]};
        r.line = line;
        out->push_back(r);
        return std::string();
      },
      &line);
}

std::string ParseEdgeRows(std::string_view text, const std::string& source,
                          std::vector<EdgeRecord>* out) {
  int64_t line = 0;
  return ForEachRow(
      text, source, 12,
      [&](const std::vector<std::string_view>& f) {
        EdgeRecord r;
        if (std::string e = FrameField(f[0], 0, false, &r.a); !e.empty()) return e;
        if (std::string e = FrameField(f[1], 1, false, &r.b); !e.empty()) return e;
        double v[9];
        if (std::string e = Numbers(f, 2, 9, v); !e.empty()) return e;
        if (std::string e = PoseRange(v, 2); !e.empty()) return e;
        r.b_in_a.mean = Pose2{v[0], v[1], v[2]};
        Mat3& c = r.b_in_a.cov;
        c << v[3], v[4], v[5], v[4], v[6], v[7], v[5], v[7], v[8];
        if (!IsPositiveDefiniteCovariance(c))
          return "covariance of edge " + std::to_string(r.a) + "-" + std::to_string(r.b) +
                 " is not positive definite (fields 6-11, c00 c01 c02 c11 c12 c22, the upper "
                 "triangle of a 3x3 covariance; atlas-replay writes positive definite ones: "
                 "re-run it or fix the row)";
        EdgeKind kind;
        if (!EdgeKindFromName(f[11], &kind))
          return "field 12 '" + std::string(f[11]) +
                 "' is not an edge kind (genesis, map-match, refined)";
        r.kind = std::string(f[11]);
        r.line = line;
        out->push_back(std::move(r));
        return std::string();
      },
      &line);
}

std::string ParseTimingRows(std::string_view text, const std::string& source,
                            std::vector<TimingRecord>* out) {
  return ForEachRow(text, source, 6, [&](const std::vector<std::string_view>& f) {
    TimingRecord r;
    int64_t frames = 0, hyps = 0;
    if (!ParseInteger(f[0], &r.step) || !ParseNumber(f[1], &r.stamp_s) ||
        !ParseInteger(f[2], &frames) || !ParseInteger(f[3], &hyps) || frames < 0 || hyps < 0 ||
        !ParseInteger(f[5], &r.step_ns))
      return std::string("expected: step timestamp frames hypotheses dominant step_ns");
    if (std::string e = FrameField(f[4], 4, true, &r.dominant); !e.empty()) return e;
    r.frames = static_cast<int>(std::min<int64_t>(frames, 100000000));
    r.hypotheses = static_cast<int>(std::min<int64_t>(hyps, 100000000));
    out->push_back(r);
    return std::string();
  });
}

std::string ParseFrameRows(std::string_view text, const std::string& source,
                           std::vector<FrameRecord>* out) {
  return ForEachRow(text, source, 4, [&](const std::vector<std::string_view>& f) {
    FrameRecord r;
    if (std::string e = FrameField(f[0], 0, false, &r.frame); !e.empty()) return e;
    if (!ParseInteger(f[1], &r.step) || !ParseNumber(f[2], &r.stamp_s))
      return std::string("expected: frame step timestamp parent");
    if (std::string e = FrameField(f[3], 3, true, &r.parent); !e.empty()) return e;
    out->push_back(r);
    return std::string();
  });
}

std::string ParseMapRows(std::string_view text, const std::string& source,
                         std::vector<FrameLine>* out) {
  return ForEachRow(text, source, 11, [&](const std::vector<std::string_view>& f) {
    FrameLine r;
    if (std::string e = FrameField(f[0], 0, false, &r.frame); !e.empty()) return e;
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
  return ForEachRow(text, source, 3, [&](const std::vector<std::string_view>& f) {
    FramePointRow r;
    if (std::string e = FrameField(f[0], 0, false, &r.frame); !e.empty()) return e;
    double v[2];
    if (std::string e = Numbers(f, 1, 2, v); !e.empty()) return e;
    r.p = Vec2(v[0], v[1]);
    out->push_back(r);
    return std::string();
  });
}

std::string ParseStampedPoses(std::string_view text, const std::string& source,
                              std::vector<StampedPose>* out) {
  return ForEachRow(text, source, 4, [&](const std::vector<std::string_view>& f) {
    double v[4];
    if (std::string e = Numbers(f, 0, 4, v); !e.empty()) return e;
    if (std::string e = StampRange(v[0], 0); !e.empty()) return e;
    if (std::string e = PoseRange(v + 1, 1); !e.empty()) return e;
    out->push_back({v[0], Pose2{v[1], v[2], v[3]}});
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
       [&](auto t, auto& s) { return ParseTrajectoryRows(t, s, &out->trajectory); }},
      {"graph.tsv", wanted.graph,
       [&](auto t, auto& s) { return ParseEdgeRows(t, s, &out->edges); }},
      {"timing.tsv", wanted.timing,
       [&](auto t, auto& s) { return ParseTimingRows(t, s, &out->timing); }},
      {"frames.tsv", wanted.frames,
       [&](auto t, auto& s) { return ParseFrameRows(t, s, &out->frames); }},
      {"maps.tsv", wanted.maps, [&](auto t, auto& s) { return ParseMapRows(t, s, &out->lines); }},
      {"points.tsv", false, [&](auto t, auto& s) { return ParsePointRows(t, s, &out->points); }},
      {"step_cpu.tsv", wanted.step_cpu,
       [&](auto t, auto& s) {
         return ForEachRow(t, s, 2, [&](const std::vector<std::string_view>& f) {
           int64_t step = 0, ns = 0;
           if (!ParseInteger(f[0], &step) || !ParseInteger(f[1], &ns) ||
               step != static_cast<int64_t>(out->step_cpu_ns.size()) + 1)
             return std::string("expected: step cpu_ns, steps counting up from 1");
           out->step_cpu_ns.push_back(ns);
           return std::string();
         });
       }},
      {"global.tsv", false, [&](auto t, auto& s) { return ParseStampedPoses(t, s, &out->global); }},
      {"global_refined.tsv", false,
       [&](auto t, auto& s) { return ParseStampedPoses(t, s, &out->refined); }},
  };
  std::vector<std::string> present;
  for (const Item& item : items) {
    const std::string path = dir + "/" + item.name;
    FileText f = ReadFile(path);
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
  if (wanted.maps && out->lines.empty())
    return empty("maps.tsv", "no frame holds a line: nothing to draw");
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
    for (const EdgeRecord& e : out->edges)
      if (std::max(e.a, e.b) >= known)
        return beyond("graph.tsv", e.line,
                      "edge " + std::to_string(e.a) + "-" + std::to_string(e.b),
                      std::max(e.a, e.b));
    for (const StampedFramePose& r : out->trajectory)
      if (r.frame >= known) return beyond("trajectory.tsv", r.line, "the row", r.frame);
  }
  int n = 0;
  for (const auto& r : out->trajectory) n = std::max(n, r.frame + 1);
  for (const auto& r : out->edges) n = std::max({n, r.a + 1, r.b + 1});
  for (const auto& r : out->timing) n = std::max({n, r.frames, r.dominant + 1});
  for (const auto& r : out->frames) n = std::max({n, r.frame + 1, r.parent + 1});
  for (const auto& r : out->lines) n = std::max(n, r.frame + 1);
  for (const auto& r : out->points) n = std::max(n, r.frame + 1);
  out->frame_count = n;
  if (has("graph.tsv") && out->edges.empty() && n > 1)
    return empty("graph.tsv", "the run has " + std::to_string(n) +
                                  " frames, and every frame after frame 0 is joined by the "
                                  "Genesis edge that made it");
  return "";
}

std::vector<std::optional<Pose2>> FramePosesFromFrameZero(const AtlasGraph& graph) {
  std::vector<std::optional<Pose2>> pose(static_cast<size_t>(graph.FrameCount()));
  if (graph.FrameCount() > 0)
    for (const ProjectedFrame& f : DijkstraProjection(graph, 0).entries)
      pose[static_cast<size_t>(f.frame)] = f.pose.mean;
  return pose;
}

std::vector<StampedPose> PlaceTrajectory(const std::vector<StampedFramePose>& trajectory,
                                         const std::vector<std::optional<Pose2>>& frame_pose) {
  std::vector<StampedPose> out;
  out.reserve(trajectory.size());
  for (const StampedFramePose& r : trajectory) {
    if (r.frame < 0 || static_cast<size_t>(r.frame) >= frame_pose.size() ||
        !frame_pose[static_cast<size_t>(r.frame)])
      continue;
    out.push_back({r.stamp_s, Compose(*frame_pose[static_cast<size_t>(r.frame)], r.pose)});
  }
  return out;
}

std::string FormatGlobalTrajectory(const std::vector<StampedFramePose>& trajectory,
                                   const std::vector<std::optional<Pose2>>& frame_pose,
                                   const std::string& comment, int* rows_written) {
  const std::vector<StampedPose> rows = PlaceTrajectory(trajectory, frame_pose);
  std::string text = "# " + comment + "\n";
  text.reserve(rows.size() * 48);
  char buf[160];
  for (const StampedPose& r : rows) {
    const int n = std::snprintf(buf, sizeof buf, "%.6f\t%.6f\t%.6f\t%.6f\n", r.stamp_s, r.pose.x,
                                r.pose.y, r.pose.theta);
    text.append(buf, static_cast<size_t>(std::clamp(n, 0, static_cast<int>(sizeof buf) - 1)));
  }
  if (rows_written != nullptr) *rows_written = static_cast<int>(rows.size());
  return text;
}

GraphFromEdges BuildGraph(const std::vector<EdgeRecord>& edges, int frame_count) {
  const auto where = [](const EdgeRecord& e) {
    return e.line > 0 ? ":" + std::to_string(e.line) : std::string();
  };
  std::vector<int> degree(static_cast<size_t>(std::max(frame_count, 0)), 0);
  for (const EdgeRecord& e : edges) {
    if (e.a < 0 || e.b < 0 || e.a >= frame_count || e.b >= frame_count) {
      return {AtlasGraph(),
              "edge " + std::to_string(e.a) + "-" + std::to_string(e.b) +
                  " names a frame outside 0.." + std::to_string(frame_count - 1),
              where(e)};
    }
    ++degree[static_cast<size_t>(e.a)];
    ++degree[static_cast<size_t>(e.b)];
  }
  const int max_degree =
      std::max(1, degree.empty() ? 1 : *std::max_element(degree.begin(), degree.end()));
  GraphFromEdges out{AtlasGraph(max_degree), "", ""};
  for (int f = 0; f < frame_count; ++f) out.graph.AddFrame(nullptr);
  for (const EdgeRecord& e : edges) {
    EdgeKind kind = EdgeKind::kGenesis;
    EdgeKindFromName(e.kind, &kind);
    const AddEdgeResult r = out.graph.AddEdge(e.a, e.b, e.b_in_a, kind);
    if (r != AddEdgeResult::kAdded) {
      out.error = "edge " + std::to_string(e.a) + "-" + std::to_string(e.b) +
                  (r == AddEdgeResult::kSameFrame ? " joins a frame to itself"
                                                  : " repeats an adjacent pair");
      out.where = where(e);
      return out;
    }
  }
  return out;
}

}  // namespace atlas::replay
