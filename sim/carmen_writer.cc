#include "sim/carmen_writer.h"

#include <charconv>
#include <cmath>
#include <cstdint>

namespace atlas::sim {
namespace {

// Fixed-point with `digits` decimals (0..9), much faster than printf or std::to_chars for the
// millions of numbers of a long run; falls back to std::to_chars for huge values.
void Fixed(std::string* out, double v, int digits, char sep = ' ') {
  static constexpr double kScale[] = {1, 1e1, 1e2, 1e3, 1e4, 1e5, 1e6, 1e7, 1e8, 1e9};
  char buf[48];
  char* end;
  const double scaled = std::round(std::abs(v) * kScale[digits]);
  if (!(scaled < 9e15)) {
    end = std::to_chars(buf, buf + sizeof(buf), v, std::chars_format::fixed, digits).ptr;
  } else {
    uint64_t n = static_cast<uint64_t>(scaled);
    char tmp[24];
    int len = 0;
    do {
      tmp[len++] = static_cast<char>('0' + n % 10);
      n /= 10;
    } while (n > 0 || len <= digits);
    end = buf;
    if (v < 0 && scaled > 0) *end++ = '-';
    for (int i = len - 1; i >= 0; --i) {
      *end++ = tmp[i];
      if (i == digits && digits > 0) *end++ = '.';
    }
  }
  out->append(buf, end);
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

void Stamps(std::string* out, Time stamp, const char* hostname = kSimHostname) {
  const double t = ToSeconds(stamp);
  Fixed(out, t, 6);
  out->append(hostname);
  out->push_back(' ');
  Fixed(out, t, 6, '\n');
}

}  // namespace

void AppendOdomLine(std::string* out, const OdometrySample& odometry, double tv, double rv,
                    const char* hostname) {
  out->append("ODOM ");
  Pose(out, odometry.pose);
  Fixed(out, tv, 4);
  Fixed(out, rv, 4);
  Fixed(out, 0.0, 1);
  Stamps(out, odometry.stamp, hostname);
}

void AppendFlaserLine(std::string* out, const LaserScan& scan, const Pose2& odometry,
                      const char* hostname) {
  out->append("FLASER ");
  Int(out, static_cast<long>(scan.ranges.size()));
  for (float r : scan.ranges) Fixed(out, IsReturn(r) ? r : kCarmenNoReturn, 3);
  Pose(out, Compose(odometry, scan.sensor_pose));
  Pose(out, odometry);
  Stamps(out, scan.stamp, hostname);
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
