#include "tools/eval/trajectory_files.h"

#include <zlib.h>

#include <algorithm>
#include <cassert>
#include <cerrno>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <utility>

#include "core/common/parse_number.h"
#include "core/geometry/covariance.h"

namespace atlas::eval {
namespace {

// Splits a line into whitespace-separated numbers; false with `error` set on a bad field.
bool ParseNumbers(std::string_view line, std::vector<double>& out, std::string& error) {
  out.clear();
  size_t i = 0;
  while (i < line.size()) {
    while (i < line.size() && (line[i] == ' ' || line[i] == '\t' || line[i] == '\r')) ++i;
    const size_t start = i;
    while (i < line.size() && line[i] != ' ' && line[i] != '\t' && line[i] != '\r') ++i;
    if (i == start) break;
    std::string_view w = line.substr(start, i - start);
    if (w[0] == '+') w.remove_prefix(1);
    double v = 0.0;
    if (!ParseNumber(w, &v)) {
      error = "field " + std::to_string(out.size() + 1) + " is " +
              carmen::QuoteForMessage(line.substr(start, i - start)) + ", not a number";
      return false;
    }
    out.push_back(v);
  }
  return true;
}

// Calls `row(line_number, numbers)` for every non-comment, non-blank line; stops at the first
// error and returns "<source>:<line>: <what>".
// With `trailing_word`, each row ends in one non-numeric word, passed to `row` as well.
// `current_line` (optional) holds the number of the line being parsed while `row` runs.
template <typename Row>
std::string ForEachRow(std::string_view text, const std::string& source, size_t fields,
                       const char* format, Row row, bool trailing_word = false,
                       size_t* current_line = nullptr) {
  std::vector<double> numbers;
  std::string error;
  size_t line_number = 0;
  size_t pos = 0;
  while (pos < text.size()) {
    size_t end = text.find('\n', pos);
    if (end == std::string_view::npos) end = text.size();
    const std::string_view line = text.substr(pos, end - pos);
    pos = end + 1;
    ++line_number;
    const size_t first = line.find_first_not_of(" \t\r");
    if (first == std::string_view::npos || line[first] == '#') continue;
    const std::string where = source + ":" + std::to_string(line_number) + ": ";
    if (current_line != nullptr) *current_line = line_number;
    std::string_view body = line.substr(0, line.find_last_not_of(" \t\r") + 1);
    std::string_view word;
    if (trailing_word) {
      const size_t cut = body.find_last_of(" \t");
      if (cut == std::string_view::npos) return where + "expected " + format;
      word = body.substr(cut + 1);
      body = body.substr(0, cut);
    }
    if (!ParseNumbers(body, numbers, error)) return where + error;
    if (numbers.size() != fields) {
      return where + "expected " + std::to_string(fields) + " numbers (" + format + "), found " +
             std::to_string(numbers.size());
    }
    if (std::string bad = row(numbers, word); !bad.empty()) return where + bad;
  }
  return {};
}

// Values no run produces, rejected before they overflow a stamp conversion (int64
// nanoseconds) or make a score NaN: "" or what is wrong, naming the 1-based field.
std::string Short(double v) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.6g", v);
  return buf;
}
std::string CheckStamp(double t, size_t field) {
  if (std::abs(t) > kMaxAbsStampS)
    return "field " + std::to_string(field) + " (a timestamp) is " + Short(t) +
           ", out of range (|t| <= 4e9 s)";
  return {};
}
std::string CheckPose(double x, double y, double theta, size_t first_field) {
  const double v[3] = {x, y, theta};
  for (size_t k = 0; k < 3; ++k) {
    const double limit = k < 2 ? kMaxAbsPositionM : kMaxAbsAngleRad;
    if (std::abs(v[k]) > limit)
      return "field " + std::to_string(first_field + k) + " is " + Short(v[k]) +
             (k < 2 ? ", out of range for a position (|x|, |y| <= 1e7 m)"
                    : ", out of range for an angle (|theta| <= 1e3 rad)");
  }
  return {};
}

// The first repeated stamp among `stamps` (with the lines they were read from), as
// "<source>:<line>: timestamp T repeats line L"; "" when all differ.
std::string RepeatedStamp(std::vector<std::pair<Time, size_t>> stamps, const std::string& source) {
  std::stable_sort(stamps.begin(), stamps.end(),
                   [](const auto& a, const auto& b) { return a.first < b.first; });
  std::string error;
  size_t worst_line = 0;
  for (size_t i = 1; i < stamps.size(); ++i) {
    if (stamps[i].first != stamps[i - 1].first) continue;
    const size_t later = std::max(stamps[i].second, stamps[i - 1].second);
    if (!error.empty() && later >= worst_line) continue;
    worst_line = later;
    char buf[64];
    std::snprintf(buf, sizeof buf, "%.6f", ToSeconds(stamps[i].first));
    error = source + ":" + std::to_string(later) + ": timestamp " + buf + " repeats line " +
            std::to_string(std::min(stamps[i].second, stamps[i - 1].second)) +
            " (one pose per stamp: remove one of the two rows)";
  }
  return error;
}

}  // namespace

TextFile ReadTextFile(const std::string& path) {
  TextFile out;
  errno = 0;
  gzFile f = gzopen(path.c_str(), "rb");
  if (f == nullptr) {
    out.error = path + ": cannot open (" + std::strerror(errno != 0 ? errno : ENOMEM) + ")";
    return out;
  }
  char buf[1 << 16];
  int n;
  while ((n = gzread(f, buf, sizeof buf)) > 0) out.text.append(buf, static_cast<size_t>(n));
  if (n < 0) {
    int zerr = 0;
    out.error = path + ": read error (" + gzerror(f, &zerr) + ")";
  }
  gzclose(f);
  return out;
}

TrajectoryParse ParseTrajectory(std::string_view text, const std::string& source) {
  TrajectoryParse out;
  std::vector<TimedPose> poses;
  std::vector<std::pair<Time, size_t>> stamps;
  size_t line = 0;
  out.error = ForEachRow(
      text, source, 4, "timestamp x y theta",
      [&](const auto& v, auto) {
        if (std::string e = CheckStamp(v[0], 1); !e.empty()) return e;
        if (std::string e = CheckPose(v[1], v[2], v[3], 2); !e.empty()) return e;
        poses.push_back(TimedPose{FromSeconds(v[0]), Pose2{v[1], v[2], WrapAngle(v[3])}});
        stamps.emplace_back(poses.back().stamp, line);
        return std::string();
      },
      false, &line);
  if (out.error.empty() && poses.empty()) out.error = source + ": no poses";
  if (out.error.empty()) out.error = RepeatedStamp(std::move(stamps), source);
  out.trajectory = TimedTrajectory(std::move(poses));
  return out;
}

RelationsParse ParseRelations(std::string_view text, const std::string& source) {
  RelationsParse out;
  out.error = ForEachRow(text, source, 8, "t1 t2 x y z roll pitch yaw", [&](const auto& v, auto) {
    if (std::string e = CheckStamp(v[0], 1); !e.empty()) return e;
    if (std::string e = CheckStamp(v[1], 2); !e.empty()) return e;
    if (std::string e = CheckPose(v[2], v[3], v[7], 3); !e.empty()) {
      // The angle is field 8 (yaw), not 5.
      return std::abs(v[7]) > kMaxAbsAngleRad ? CheckPose(0, 0, v[7], 6) : e;
    }
    out.relations.push_back(
        Relation{FromSeconds(v[0]), FromSeconds(v[1]), Pose2{v[2], v[3], WrapAngle(v[7])}});
    return std::string();
  });
  if (out.error.empty() && out.relations.empty()) out.error = source + ": no relations";
  return out;
}

namespace {

bool IsFrameId(double v) { return v == std::floor(v) && v >= 0 && v < (1 << 30); }

}  // namespace

FramePosesParse ParseFrameTrajectory(std::string_view text, const std::string& source) {
  FramePosesParse out;
  std::vector<std::pair<Time, size_t>> stamps;
  size_t line = 0;
  out.error = ForEachRow(
      text, source, 5, "timestamp frame x y theta",
      [&](const auto& v, auto) {
        if (std::string e = CheckStamp(v[0], 1); !e.empty()) return e;
        if (!IsFrameId(v[1])) return std::string("the frame is not a frame id (integer >= 0)");
        if (std::string e = CheckPose(v[2], v[3], v[4], 3); !e.empty()) return e;
        out.rows.push_back(FramePose{FromSeconds(v[0]), static_cast<FrameId>(v[1]),
                                     Pose2{v[2], v[3], WrapAngle(v[4])}});
        out.lines.push_back(line);
        stamps.emplace_back(out.rows.back().stamp, line);
        return std::string();
      },
      false, &line);
  if (out.error.empty() && out.rows.empty()) out.error = source + ": no poses";
  if (out.error.empty()) out.error = RepeatedStamp(std::move(stamps), source);
  return out;
}

EdgeRowsParse ParseGraphEdges(std::string_view text, const std::string& source) {
  EdgeRowsParse out;
  size_t line = 0;
  std::map<std::pair<FrameId, FrameId>, size_t> pairs;  // the line of each joined pair
  out.error = ForEachRow(
      text, source, 11, "from to x y theta c00 c01 c02 c11 c12 c22 kind",
      [&](const auto& v, std::string_view word) {
        if (!IsFrameId(v[0]) || !IsFrameId(v[1]))
          return std::string("from and to must be frame ids (integers >= 0)");
        EdgeRow e;
        e.from = static_cast<FrameId>(v[0]);
        e.to = static_cast<FrameId>(v[1]);
        const std::string name = std::to_string(e.from) + "-" + std::to_string(e.to);
        if (e.from == e.to) return "edge " + name + " joins a frame to itself";
        if (std::string bad = CheckPose(v[2], v[3], v[4], 3); !bad.empty()) return bad;
        e.to_in_from.mean = Pose2{v[2], v[3], WrapAngle(v[4])};
        e.to_in_from.cov << v[5], v[6], v[7], v[6], v[8], v[9], v[7], v[9], v[10];
        if (!IsPositiveDefiniteCovariance(e.to_in_from.cov)) {
          return "covariance of edge " + name +
                 " is not positive definite (fields 6-11, c00 c01 c02 c11 c12 c22, the upper "
                 "triangle of a 3x3 covariance; atlas-replay writes positive definite ones: "
                 "re-run it or fix the row)";
        }
        bool known = false;
        for (EdgeKind k : {EdgeKind::kGenesis, EdgeKind::kMapMatch, EdgeKind::kRefined}) {
          if (word == EdgeKindName(k)) {
            e.kind = k;
            known = true;
          }
        }
        if (!known) {
          return "kind is " + carmen::QuoteForMessage(word) + ", not genesis, map-match or refined";
        }
        const std::pair<FrameId, FrameId> key{std::min(e.from, e.to), std::max(e.from, e.to)};
        if (const auto it = pairs.find(key); it != pairs.end())
          return "edge " + name + " joins two frames that line " + std::to_string(it->second) +
                 " already joins";
        pairs.emplace(key, line);
        out.frame_count = std::max(out.frame_count, std::max(e.from, e.to) + 1);
        out.rows.push_back(e);
        out.lines.push_back(line);
        return std::string();
      },
      /*trailing_word=*/true, &line);
  return out;
}

int64_t ParseFrameCount(std::string_view text, const std::string& source, std::string* error) {
  int64_t count = 0;
  *error = ForEachRow(text, source, 4, "frame step timestamp parent", [&](const auto& v, auto) {
    if (!IsFrameId(v[0])) return std::string("the frame is not a frame id (integer >= 0)");
    count = std::max(count, static_cast<int64_t>(v[0]) + 1);
    return std::string();
  });
  return error->empty() ? count : -1;
}

std::string CheckFramesExist(const FramePosesParse& trajectory,
                             const std::string& trajectory_source, const EdgeRowsParse& edges,
                             const std::string& graph_source, int64_t frame_count,
                             const std::string& count_source) {
  const auto beyond = [&](const std::string& source, size_t line, const std::string& what,
                          FrameId f) {
    return source + ":" + std::to_string(line) + ": " + what + " names frame " + std::to_string(f) +
           ", but " + count_source + " lists " + std::to_string(frame_count) +
           " frames; the files are not from one run, or the row is damaged";
  };
  if (frame_count >= 0) {
    for (size_t i = 0; i < edges.rows.size(); ++i) {
      const EdgeRow& e = edges.rows[i];
      if (std::max(e.from, e.to) >= frame_count)
        return beyond(graph_source, edges.lines[i],
                      "edge " + std::to_string(e.from) + "-" + std::to_string(e.to),
                      std::max(e.from, e.to));
    }
    for (size_t i = 0; i < trajectory.rows.size(); ++i)
      if (trajectory.rows[i].frame >= frame_count)
        return beyond(trajectory_source, trajectory.lines[i], "the row", trajectory.rows[i].frame);
  }
  int frames = static_cast<int>(std::max<int64_t>(frame_count, edges.frame_count));
  for (const FramePose& r : trajectory.rows) frames = std::max(frames, r.frame + 1);
  if (edges.rows.empty() && frames > 1)
    return graph_source + ": no edges, but the atlas has " + std::to_string(frames) +
           " frames (every frame after frame 0 is joined by the Genesis edge that made it)";
  return {};
}

std::string FormatTrajectory(const TimedTrajectory& trajectory, const std::string& comment) {
  std::string out = "# " + comment + "\n# timestamp x y theta\n";
  char buf[128];
  for (const TimedPose& p : trajectory.poses()) {
    std::snprintf(buf, sizeof buf, "%.6f\t%.6f\t%.6f\t%.6f\n", ToSeconds(p.stamp), p.pose.x,
                  p.pose.y, p.pose.theta);
    out += buf;
  }
  return out;
}

std::string FormatRelationErrors(const std::vector<Relation>& relations,
                                 const RelationsScore& score, std::span<const FrameJoin> joins) {
  assert(joins.empty() || joins.size() == score.errors.size());
  std::string out = "# atlas-eval relation errors: t1 t2 translation_m rotation_deg";
  out += joins.empty() ? "\n" : " join\n";
  char buf[160];
  for (size_t i = 0; i < score.errors.size(); ++i) {
    const RelationError& e = score.errors[i];
    const Relation& r = relations[e.relation];
    std::snprintf(buf, sizeof buf, "%.6f %.6f %.6f %.6f%s%s\n", ToSeconds(r.t1), ToSeconds(r.t2),
                  e.translation_m, e.rotation_deg, joins.empty() ? "" : " ",
                  joins.empty() ? "" : FrameJoinName(joins[i]));
    out += buf;
  }
  return out;
}

TimedTrajectory OdometryAtScans(const std::vector<carmen::CarmenEvent>& events) {
  std::vector<OdometrySample> odometry;
  for (const carmen::CarmenEvent& e : events) {
    if (const auto* o = std::get_if<OdometrySample>(&e.event)) odometry.push_back(*o);
  }
  std::vector<TimedPose> poses;
  for (const carmen::CarmenEvent& e : events) {
    const auto* scan = std::get_if<LaserScan>(&e.event);
    if (scan == nullptr) continue;
    const Time t = scan->stamp;
    // The last sample at or before t.
    auto after = std::upper_bound(odometry.begin(), odometry.end(), t,
                                  [](Time x, const OdometrySample& o) { return x < o.stamp; });
    if (after == odometry.begin()) continue;
    const OdometrySample& a = *std::prev(after);
    if (a.stamp == t) {
      poses.push_back(TimedPose{t, a.pose});
      continue;
    }
    if (after == odometry.end()) continue;
    const OdometrySample& b = *after;
    const double f = ToSeconds(t - a.stamp) / ToSeconds(b.stamp - a.stamp);
    const Pose2 p{a.pose.x + f * (b.pose.x - a.pose.x), a.pose.y + f * (b.pose.y - a.pose.y),
                  WrapAngle(a.pose.theta + f * WrapAngle(b.pose.theta - a.pose.theta))};
    poses.push_back(TimedPose{t, p});
  }
  return TimedTrajectory(std::move(poses));
}

TimedTrajectory ReferenceAtScans(const carmen::CarmenLog& log) {
  std::vector<TimedPose> poses;
  for (const carmen::ReferencePose& r : log.reference) {
    if (r.at_laser) poses.push_back(TimedPose{r.truth.stamp, r.truth.pose});
  }
  return TimedTrajectory(std::move(poses));
}

std::string FormatStats(const char* name, const char* unit, const ErrorStats& s) {
  char buf[256];
  std::snprintf(buf, sizeof buf,
                "%-14s %8.4f +- %8.4f %-3s (squared %9.4f +- %9.4f, rmse %8.4f, max %8.4f)\n", name,
                s.mean, s.stddev, unit, s.mean_squared, s.stddev_squared, s.rmse, s.max);
  return buf;
}

std::string StatsJson(const ErrorStats& s) {
  char buf[320];
  std::snprintf(buf, sizeof buf,
                "{\"count\": %lld, \"mean\": %.6g, \"stddev\": %.6g, \"mean_squared\": %.6g, "
                "\"stddev_squared\": %.6g, \"rmse\": %.6g, \"max\": %.6g}",
                static_cast<long long>(s.count), s.mean, s.stddev, s.mean_squared, s.stddev_squared,
                s.rmse, s.max);
  return buf;
}

std::string JsonString(std::string_view s) {
  std::string out = "\"";
  for (char c : s) {
    if (c == '"' || c == '\\') {
      out += '\\';
      out += c;
    } else if (static_cast<unsigned char>(c) < 0x20) {
      char buf[8];
      std::snprintf(buf, sizeof buf, "\\u%04x", c);
      out += buf;
    } else {
      out += c;
    }
  }
  return out + "\"";
}

}  // namespace atlas::eval
