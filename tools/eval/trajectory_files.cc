#include "tools/eval/trajectory_files.h"

#include <zlib.h>

#include <algorithm>
#include <cassert>
#include <cerrno>
#include <charconv>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>

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
    auto [ptr, ec] = std::from_chars(w.data(), w.data() + w.size(), v);
    if (ec != std::errc() || ptr != w.data() + w.size() || !std::isfinite(v)) {
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
template <typename Row>
std::string ForEachRow(std::string_view text, const std::string& source, size_t fields,
                       const char* format, Row row, bool trailing_word = false) {
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
  out.error = ForEachRow(text, source, 4, "timestamp x y theta", [&](const auto& v, auto) {
    poses.push_back(TimedPose{FromSeconds(v[0]), Pose2{v[1], v[2], WrapAngle(v[3])}});
    return std::string();
  });
  if (out.error.empty() && poses.empty()) out.error = source + ": no poses";
  out.trajectory = TimedTrajectory(std::move(poses));
  return out;
}

RelationsParse ParseRelations(std::string_view text, const std::string& source) {
  RelationsParse out;
  out.error = ForEachRow(text, source, 8, "t1 t2 x y z roll pitch yaw", [&](const auto& v, auto) {
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
  out.error = ForEachRow(text, source, 5, "timestamp frame x y theta", [&](const auto& v, auto) {
    if (!IsFrameId(v[1])) return std::string("the frame is not a frame id (integer >= 0)");
    out.rows.push_back(FramePose{FromSeconds(v[0]), static_cast<FrameId>(v[1]),
                                 Pose2{v[2], v[3], WrapAngle(v[4])}});
    return std::string();
  });
  if (out.error.empty() && out.rows.empty()) out.error = source + ": no poses";
  return out;
}

EdgeRowsParse ParseGraphEdges(std::string_view text, const std::string& source) {
  EdgeRowsParse out;
  out.error = ForEachRow(
      text, source, 11, "from to x y theta c00 c01 c02 c11 c12 c22 kind",
      [&](const auto& v, std::string_view word) {
        if (!IsFrameId(v[0]) || !IsFrameId(v[1]))
          return std::string("from and to must be frame ids (integers >= 0)");
        EdgeRow e;
        e.from = static_cast<FrameId>(v[0]);
        e.to = static_cast<FrameId>(v[1]);
        e.to_in_from.mean = Pose2{v[2], v[3], WrapAngle(v[4])};
        e.to_in_from.cov << v[5], v[6], v[7], v[6], v[8], v[9], v[7], v[9], v[10];
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
        out.frame_count = std::max(out.frame_count, std::max(e.from, e.to) + 1);
        out.rows.push_back(e);
        return std::string();
      },
      /*trailing_word=*/true);
  return out;
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

bool ParseArgumentNumber(const char* s, double& out) {
  char* end = nullptr;
  out = std::strtod(s, &end);
  return end != s && *end == '\0' && std::isfinite(out);
}

ToolOptions ParseToolOptions(int argc, char** argv, int first,
                             const std::vector<std::string>& known) {
  ToolOptions a;
  for (int i = first; i < argc; ++i) {
    const std::string k = argv[i];
    if (std::find(known.begin(), known.end(), k) == known.end()) {
      a.error = "unknown option '" + k + "'";
      return a;
    }
    if (i + 1 >= argc) {
      a.error = "option '" + k + "' needs a value";
      return a;
    }
    a.values[k] = argv[++i];
  }
  return a;
}

bool GetNumberOption(const ToolOptions& options, const std::string& key, double lo, double hi,
                     double& out, std::string& error) {
  auto it = options.values.find(key);
  if (it == options.values.end()) return true;
  double v = 0.0;
  if (!ParseArgumentNumber(it->second.c_str(), v) || v < lo || v > hi) {
    error = key + " must be a number in [" + std::to_string(lo) + ", " + std::to_string(hi) +
            "], got '" + it->second + "'";
    return false;
  }
  out = v;
  return true;
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
