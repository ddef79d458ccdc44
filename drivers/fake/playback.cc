#include "drivers/fake/playback.h"

#include <algorithm>
#include <cmath>

#include "logs/carmen/carmen_log.h"

namespace atlas::fake {

Pose2 Recording::OdometryAt(Time t) const {
  if (t <= odometry.front().stamp) return odometry.front().pose;
  if (t >= odometry.back().stamp) return odometry.back().pose;
  auto it = std::upper_bound(odometry.begin(), odometry.end(), t,
                             [](Time v, const OdometrySample& s) { return v < s.stamp; });
  const OdometrySample& b = *it;
  const OdometrySample& a = *(it - 1);
  const double span = ToSeconds(b.stamp - a.stamp);
  const double u = span > 0 ? ToSeconds(t - a.stamp) / span : 1.0;
  return Pose2{a.pose.x + u * (b.pose.x - a.pose.x), a.pose.y + u * (b.pose.y - a.pose.y),
               WrapAngle(a.pose.theta + u * WrapAngle(b.pose.theta - a.pose.theta))};
}

bool LoadCarmenRecording(const std::string& path, size_t max_scans, Recording* out,
                         std::string* error) {
  carmen::CarmenReadResult r = carmen::ReadCarmenLog(path, carmen::CarmenLogOptions{});
  if (!r.ok()) {
    *error = r.error;
    return false;
  }
  Recording rec;
  for (carmen::CarmenEvent& e : r.log.events) {
    if (auto* s = std::get_if<LaserScan>(&e.event)) {
      if (max_scans > 0 && rec.scans.size() >= max_scans) break;
      rec.scans.push_back(std::move(*s));
    } else if (auto* o = std::get_if<OdometrySample>(&e.event)) {
      rec.odometry.push_back(*o);
    }
  }
  if (rec.scans.empty()) {
    *error = path + ": no laser scans in the log";
    return false;
  }
  if (rec.odometry.empty()) {
    *error = path + ": no odometry in the log";
    return false;
  }
  rec.begin = std::min(rec.scans.front().stamp, rec.odometry.front().stamp);
  rec.end = std::max(rec.scans.back().stamp, rec.odometry.back().stamp);
  if (max_scans > 0) {
    rec.end = rec.scans.back().stamp;
    while (rec.odometry.size() > 1 && rec.odometry.back().stamp > rec.end) rec.odometry.pop_back();
  }
  *out = std::move(rec);
  return true;
}

}  // namespace atlas::fake
