#include "tools/eval/trajectory_files.h"

#include <algorithm>
#include <cassert>
#include <cmath>
#include <cstdio>
#include <utility>

#include "formats/pose_file.h"
#include "formats/text_rows.h"

namespace atlas::eval {

TrajectoryParse ParseTrajectory(std::string_view text, const std::string& source) {
  TrajectoryParse out;
  formats::PoseRows rows = formats::ParsePoseRows(text, source);
  out.error = std::move(rows.error);
  if (out.error.empty() && rows.poses.empty()) out.error = source + ": no poses";
  out.trajectory = TimedTrajectory(std::move(rows.poses));
  return out;
}

RelationsParse ParseRelations(std::string_view text, const std::string& source) {
  RelationsParse out;
  out.error = formats::ForEachRow(
      text, source, 8, "t1 t2 x y z roll pitch yaw",
      [&](std::span<const std::string_view> f, int64_t) {
        Relation r;
        double v[6];
        if (std::string e = formats::StampField(f[0], 1, &r.t1); !e.empty()) return e;
        if (std::string e = formats::StampField(f[1], 2, &r.t2); !e.empty()) return e;
        for (size_t k = 0; k < 6; ++k) {
          // x, y and yaw (field 8) are used; z, roll and pitch must be numbers.
          const bool used = k < 2 || k == 5;
          if (std::string e = used ? formats::CoordinateField(f[2 + k], 3 + k, k == 5, &v[k])
                                   : formats::NumberField(f[2 + k], 3 + k, &v[k]);
              !e.empty())
            return e;
        }
        r.delta = Pose2{v[0], v[1], WrapAngle(v[5])};
        out.relations.push_back(r);
        return std::string();
      });
  if (out.error.empty() && out.relations.empty()) out.error = source + ": no relations";
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
