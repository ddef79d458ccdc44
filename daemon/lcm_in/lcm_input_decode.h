#pragma once
// LCM messages of the input mode (input.source = "lcm", docs/lcm.md "LCM input") -> the plain
// structs the device drivers produce (core/common/sensor_types.h). Pure: bytes or a decoded
// message in, a LaserScan or OdometrySample (or why not) out; the subscriber (lcm_input.h)
// owns the LCM instance.
//
// - Every sample is stamped with `arrival` (the monotonic clock when the message came), never
//   with its utime: the publisher's clock may be another host's or an epoch clock.
// - atlasd.laser_scan_t / atlasd.odometry_t: as FromLaserMessage / FromOdometryMessage
//   (daemon/lcm_out/lcm_convert.h), the mount and maximum range from the message; a negative
//   range is no return.
// - bot_core.planar_lidar_t: beam i at rad0 + i * radstep; the mount and maximum range are the
//   configuration's (LaserSetup); a range not above 0 or not finite is no return (kNoReturn).
//   Intensities are not used.
// - DecodeLaserMessage applies LaserSetup's max_range to either type as the scanner's range
//   setting (LimitLaserRange: a range at or beyond it is no return, and the scan's maximum is at
//   most it), so atlasd's laser.max_range_m holds for every laser source.
// - bot_core.pose_t: x, y of pos; theta the yaw of the quaternion orientation (w, x, y, z),
//   which need not be normalised. z, velocities and accelerations are not used.
// A message that does not decode as the configured type (another type on the channel), or
// holds what no scan or pose can (no beams, a zero or non-finite angle step, a zero quaternion,
// non-finite numbers), gives an error in words and no sample: the daemon counts it and goes on.

#include <cstdint>
#include <optional>
#include <span>
#include <string>

#include "atlasd/laser_scan_t.hpp"
#include "atlasd/odometry_t.hpp"
#include "bot_core/planar_lidar_t.hpp"
#include "bot_core/pose_t.hpp"
#include "core/common/sensor_types.h"
#include "formats/config/daemon_options.h"

namespace atlas {

// What a laser message does not say, for the types that do not carry it (planar_lidar_t).
struct LaserSetup {
  Pose2 sensor_pose;       // the scanner on the robot
  float max_range = 8.0f;  // metres
};

// A sample, or the reason there is none.
template <typename T>
struct Decoded {
  std::optional<T> sample;
  std::string error;
};

// Beams accepted in one scan; more is not a planar scanner (and not a reasonable message).
inline constexpr int32_t kMaxInputBeams = 100000;

Decoded<LaserScan> FromAtlasLaserScan(const atlasd::laser_scan_t& m, Time arrival);
Decoded<LaserScan> FromPlanarLidar(const bot_core::planar_lidar_t& m, const LaserSetup& setup,
                                   Time arrival);
Decoded<OdometrySample> FromAtlasOdometry(const atlasd::odometry_t& m, Time arrival);
Decoded<OdometrySample> FromBotPose(const bot_core::pose_t& m, Time arrival);

// Heading (rotation about z, counter-clockwise, radians in (-pi, pi]) of the quaternion
// w + xi + yj + zk, normalised or not.
double YawOfQuaternion(double w, double x, double y, double z);

// The bytes of one LCM message (fingerprint first) as `type`.
Decoded<LaserScan> DecodeLaserMessage(LaserMessageType type, std::span<const uint8_t> bytes,
                                      const LaserSetup& setup, Time arrival);
Decoded<OdometrySample> DecodeOdometryMessage(OdometryMessageType type,
                                              std::span<const uint8_t> bytes, Time arrival);

// When LCM received a message, on the monotonic clock: `recv_utime` is LCM's receive time in
// microseconds of the realtime clock (with udpm when the packet came: a message handled 200 ms
// after it was sent carries a receive time 200 ms old), moved by the two clocks' offset now
// (`realtime_now_us`, `monotonic_now`, read together). A receive time after now or more than
// kMaxReceiveAge before it (a realtime clock step, a provider that leaves it 0) gives
// `monotonic_now`.
inline constexpr Duration kMaxReceiveAge = std::chrono::seconds(1);
Time ArrivalOnMonotonicClock(int64_t recv_utime, int64_t realtime_now_us, Time monotonic_now);

// The configuration's name of a type ("laser_scan_t", "bot_core.planar_lidar_t", ...).
const char* InputTypeName(LaserMessageType type);
const char* InputTypeName(OdometryMessageType type);

}  // namespace atlas
