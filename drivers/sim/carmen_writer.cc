#include "drivers/sim/carmen_writer.h"

#include <charconv>

namespace atlas::sim {
namespace {

void Fixed(std::string* out, double v, int digits, char sep = ' ') {
  char buf[48];
  if (v == 0.0) v = 0.0;  // no "-0.000"
  const auto r = std::to_chars(buf, buf + sizeof(buf), v, std::chars_format::fixed, digits);
  out->append(buf, r.ptr);
  out->push_back(sep);
}

void Int(std::string* out, long v) {
  char buf[24];
  const auto r = std::to_chars(buf, buf + sizeof(buf), v);
  out->append(buf, r.ptr);
  out->push_back(' ');
}

void Pose(std::string* out, const Pose2& p) {
  Fixed(out, p.x, 4);
  Fixed(out, p.y, 4);
  Fixed(out, p.theta, 5);
}

void Stamps(std::string* out, Time stamp) {
  const double t = ToSeconds(stamp);
  Fixed(out, t, 6);
  out->append(kSimHostname);
  out->push_back(' ');
  Fixed(out, t, 6, '\n');
}

}  // namespace

void AppendOdomLine(std::string* out, const OdometrySample& odometry, double tv, double rv) {
  out->append("ODOM ");
  Pose(out, odometry.pose);
  Fixed(out, tv, 4);
  Fixed(out, rv, 4);
  Fixed(out, 0.0, 1);
  Stamps(out, odometry.stamp);
}

void AppendFlaserLine(std::string* out, const LaserScan& scan, const Pose2& odometry) {
  out->append("FLASER ");
  Int(out, static_cast<long>(scan.ranges.size()));
  for (float r : scan.ranges) Fixed(out, IsReturn(r) ? r : kCarmenNoReturn, 3);
  Pose(out, Compose(odometry, scan.sensor_pose));
  Pose(out, odometry);
  Stamps(out, scan.stamp);
}

void AppendSonarLine(std::string* out, const SonarReading& reading, const Pose2& odometry) {
  out->append("SONAR ");
  Int(out, static_cast<long>(reading.returns.size()));
  for (const SonarReturn& r : reading.returns) {
    Int(out, r.transducer);
    Fixed(out, IsReturn(r.range) ? r.range : -1.0, 3);
  }
  Pose(out, odometry);
  Stamps(out, reading.stamp);
}

void AppendTruthRow(std::string* out, const TruthSample& truth) {
  Fixed(out, ToSeconds(truth.stamp), 6, '\t');
  Fixed(out, truth.pose.x, 5, '\t');
  Fixed(out, truth.pose.y, 5, '\t');
  Fixed(out, truth.pose.theta, 6, '\n');
}

}  // namespace atlas::sim
