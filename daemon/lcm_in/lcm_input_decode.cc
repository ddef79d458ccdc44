#include "daemon/lcm_in/lcm_input_decode.h"

#include <cmath>

#include "daemon/lcm_out/lcm_convert.h"

namespace atlas {
namespace {

bool Finite(std::initializer_list<double> values) {
  for (double v : values)
    if (!std::isfinite(v)) return false;
  return true;
}

std::string CheckBeams(int32_t n, double angle_min, double step) {
  if (n <= 0) return "a scan without ranges";
  if (n > kMaxInputBeams) return "more than " + std::to_string(kMaxInputBeams) + " ranges";
  if (!Finite({angle_min, step}) || step == 0.0)
    return "the first bearing or the angle step is not a finite number, or the step is 0";
  return "";
}

// The int32 at `offset` of an LCM message (big-endian), or -1 beyond its end.
int64_t Int32At(std::span<const uint8_t> b, size_t offset) {
  if (offset + 4 > b.size()) return -1;
  const uint32_t v = (uint32_t{b[offset]} << 24) | (uint32_t{b[offset + 1]} << 16) |
                     (uint32_t{b[offset + 2]} << 8) | uint32_t{b[offset + 3]};
  return static_cast<int32_t>(v);
}

// The array lengths of a message are checked against its size before lcm-gen's decode, which
// would otherwise allocate what a corrupt length field asks for. `count_at` is the offset of
// the first length field; each is followed by that many 4-byte elements, then the next field.
bool ArraysFit(std::span<const uint8_t> b, size_t count_at, int arrays) {
  size_t at = count_at;
  for (int i = 0; i < arrays; ++i) {
    const int64_t n = Int32At(b, at);
    if (n < 0 || static_cast<uint64_t>(n) > (b.size() - at - 4) / 4) return false;
    at += 4 + 4 * static_cast<size_t>(n);
  }
  return true;
}

template <typename M>
bool DecodeBytes(std::span<const uint8_t> bytes, M* m) {
  return m->decode(bytes.data(), 0, static_cast<int>(bytes.size())) >= 0;
}

std::string NotA(const char* type, const char* key) {
  return std::string("not a ") + type +
         " (another type on the channel, or a damaged message): check input." + key;
}

}  // namespace

const char* InputTypeName(LaserMessageType type) {
  return type == LaserMessageType::kPlanarLidar ? "bot_core.planar_lidar_t" : "laser_scan_t";
}
const char* InputTypeName(OdometryMessageType type) {
  return type == OdometryMessageType::kBotPose ? "bot_core.pose_t" : "odometry_t";
}

double YawOfQuaternion(double w, double x, double y, double z) {
  // atan2 of the rotated x axis's y and x components; a common scale of w, x, y, z cancels.
  return std::atan2(2.0 * (w * z + x * y), w * w + x * x - y * y - z * z);
}

Decoded<LaserScan> FromAtlasLaserScan(const atlasd::laser_scan_t& m, Time arrival) {
  Decoded<LaserScan> d;
  d.error = CheckBeams(m.num_ranges, m.angle_min, m.angle_increment);
  if (d.error.empty() && (!Finite({m.sensor_x, m.sensor_y, m.sensor_theta}) ||
                          !std::isfinite(m.max_range) || m.max_range <= 0.0f))
    d.error = "the mount or the maximum range is not a finite number, or the range is not above 0";
  if (!d.error.empty()) return d;
  LaserScan s = FromLaserMessage(m);
  s.stamp = arrival;
  for (float& r : s.ranges)
    if (r < 0.0f) r = kNoReturn;
  d.sample = std::move(s);
  return d;
}

Decoded<LaserScan> FromPlanarLidar(const bot_core::planar_lidar_t& m, const LaserSetup& setup,
                                   Time arrival) {
  Decoded<LaserScan> d;
  d.error = CheckBeams(m.nranges, m.rad0, m.radstep);
  if (!d.error.empty()) return d;
  LaserScan s;
  s.stamp = arrival;
  s.angle_min = m.rad0;
  s.angle_increment = m.radstep;
  s.max_range = setup.max_range;
  s.sensor_pose = setup.sensor_pose;
  s.ranges = m.ranges;
  for (float& r : s.ranges)
    if (!std::isfinite(r) || r <= 0.0f) r = kNoReturn;
  d.sample = std::move(s);
  return d;
}

Decoded<OdometrySample> FromAtlasOdometry(const atlasd::odometry_t& m, Time arrival) {
  Decoded<OdometrySample> d;
  if (!Finite({m.x, m.y, m.theta})) {
    d.error = "the pose is not finite";
    return d;
  }
  OdometrySample s = FromOdometryMessage(m);
  s.stamp = arrival;
  s.pose.theta = WrapAngle(s.pose.theta);
  d.sample = s;
  return d;
}

Decoded<OdometrySample> FromBotPose(const bot_core::pose_t& m, Time arrival) {
  Decoded<OdometrySample> d;
  const double* q = m.orientation;
  if (!Finite({m.pos[0], m.pos[1], q[0], q[1], q[2], q[3]})) {
    d.error = "the position or the orientation is not finite";
    return d;
  }
  if (q[0] * q[0] + q[1] * q[1] + q[2] * q[2] + q[3] * q[3] < 1e-12) {
    d.error = "the orientation quaternion is zero";
    return d;
  }
  OdometrySample s;
  s.stamp = arrival;
  s.pose = Pose2{m.pos[0], m.pos[1], YawOfQuaternion(q[0], q[1], q[2], q[3])};
  d.sample = s;
  return d;
}

Decoded<LaserScan> DecodeLaserMessage(LaserMessageType type, std::span<const uint8_t> bytes,
                                      const LaserSetup& setup, Time arrival) {
  // Offsets of the first array length: 8 bytes of fingerprint, then the fields before it.
  Decoded<LaserScan> d;
  if (type == LaserMessageType::kPlanarLidar) {
    bot_core::planar_lidar_t m;
    if (!ArraysFit(bytes, 8 + 8, 2) || !DecodeBytes(bytes, &m))
      return {std::nullopt, NotA("bot_core.planar_lidar_t", "laser_type")};
    d = FromPlanarLidar(m, setup, arrival);
  } else {
    atlasd::laser_scan_t m;
    if (!ArraysFit(bytes, 8 + 8 + 3 * 4, 1) || !DecodeBytes(bytes, &m))
      return {std::nullopt, NotA("atlasd.laser_scan_t", "laser_type")};
    d = FromAtlasLaserScan(m, arrival);
  }
  if (d.sample) LimitLaserRange(&*d.sample, setup.max_range);  // the scanner's range setting
  return d;
}

Decoded<OdometrySample> DecodeOdometryMessage(OdometryMessageType type,
                                              std::span<const uint8_t> bytes, Time arrival) {
  if (type == OdometryMessageType::kBotPose) {
    bot_core::pose_t m;
    if (!DecodeBytes(bytes, &m)) return {std::nullopt, NotA("bot_core.pose_t", "odometry_type")};
    return FromBotPose(m, arrival);
  }
  atlasd::odometry_t m;
  if (!DecodeBytes(bytes, &m)) return {std::nullopt, NotA("atlasd.odometry_t", "odometry_type")};
  return FromAtlasOdometry(m, arrival);
}

Time ArrivalOnMonotonicClock(int64_t recv_utime, int64_t realtime_now_us, Time monotonic_now) {
  const int64_t age_us = realtime_now_us - recv_utime;
  if (recv_utime <= 0 || age_us < 0 ||
      age_us > std::chrono::duration_cast<std::chrono::microseconds>(kMaxReceiveAge).count())
    return monotonic_now;
  return monotonic_now - std::chrono::microseconds(age_us);
}

}  // namespace atlas
