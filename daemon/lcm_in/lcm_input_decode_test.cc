#include "daemon/lcm_in/lcm_input_decode.h"

#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include "daemon/lcm_out/lcm_convert.h"

namespace atlas {
namespace {

template <typename M>
std::vector<uint8_t> Encoded(const M& m) {
  std::vector<uint8_t> b(static_cast<size_t>(m.getEncodedSize()));
  EXPECT_EQ(m.encode(b.data(), 0, static_cast<int>(b.size())), static_cast<int>(b.size()));
  return b;
}

bot_core::planar_lidar_t Lidar(std::vector<float> ranges) {
  bot_core::planar_lidar_t m{};
  m.utime = 1796166934722075;  // an epoch utime: not the stamp
  m.nranges = static_cast<int32_t>(ranges.size());
  m.ranges = std::move(ranges);
  m.nintensities = 2;
  m.intensities = {10.0f, 20.0f};
  m.rad0 = -1.5f;
  m.radstep = 0.25f;
  return m;
}

bot_core::pose_t BotPose(double x, double y, double yaw) {
  bot_core::pose_t m{};
  m.utime = 42;
  m.pos[0] = x;
  m.pos[1] = y;
  m.pos[2] = 7.0;
  m.orientation[0] = std::cos(yaw / 2);
  m.orientation[3] = std::sin(yaw / 2);
  return m;
}

const LaserSetup kSetup{Pose2{0.1, -0.05, 0.02}, 8.0f};
const Time kArrival = FromSeconds(123.456789);

TEST(LcmInputDecodeTest, PlanarLidarBytesBecomeAScanStampedAtArrival) {
  const auto bytes = Encoded(Lidar({1.0f, 0.0f, -1.0f, 9.0f, NAN, 2.5f}));
  const Decoded<LaserScan> d =
      DecodeLaserMessage(LaserMessageType::kPlanarLidar, bytes, kSetup, kArrival);
  ASSERT_TRUE(d.sample) << d.error;
  const LaserScan& s = *d.sample;
  EXPECT_EQ(s.stamp, kArrival);
  EXPECT_EQ(s.angle_min, -1.5f);
  EXPECT_EQ(s.angle_increment, 0.25f);
  EXPECT_EQ(s.max_range, 8.0f);
  EXPECT_EQ(s.sensor_pose.x, 0.1);
  EXPECT_EQ(s.sensor_pose.theta, 0.02);
  ASSERT_EQ(s.ranges.size(), 6u);
  EXPECT_EQ(s.ranges[0], 1.0f);
  // Not above 0, beyond the maximum range, not a number: no return.
  for (int i : {1, 2, 3, 4}) EXPECT_FALSE(IsReturn(s.ranges[i])) << i;
  EXPECT_EQ(s.ranges[5], 2.5f);
}

// The message's own maximum holds below the configured one (laser.max_range_m), which caps it.
TEST(LcmInputDecodeTest, AtlasLaserScanBytesKeepTheirMountAndRanges) {
  LaserScan in;
  in.stamp = FromSeconds(5);
  in.angle_min = -1.0f;
  in.angle_increment = 0.5f;
  in.max_range = 50.0f;
  in.ranges = {1.0f, kNoReturn, 40.0f, -2.0f};
  in.sensor_pose = Pose2{0.3, 0.0, 0.1};
  const auto bytes = Encoded(ToLaserMessage(in));
  const LaserSetup long_range{kSetup.sensor_pose, 60.0f};
  const Decoded<LaserScan> d =
      DecodeLaserMessage(LaserMessageType::kLaserScan, bytes, long_range, kArrival);
  ASSERT_TRUE(d.sample) << d.error;
  EXPECT_EQ(d.sample->stamp, kArrival);
  EXPECT_EQ(d.sample->max_range, 50.0f);
  EXPECT_EQ(d.sample->sensor_pose.x, 0.3);
  ASSERT_EQ(d.sample->ranges.size(), 4u);
  EXPECT_EQ(d.sample->ranges[2], 40.0f);
  EXPECT_FALSE(IsReturn(d.sample->ranges[1]));
  EXPECT_FALSE(IsReturn(d.sample->ranges[3]));
  const Decoded<LaserScan> capped =
      DecodeLaserMessage(LaserMessageType::kLaserScan, bytes, kSetup, kArrival);
  ASSERT_TRUE(capped.sample) << capped.error;
  EXPECT_EQ(capped.sample->max_range, 8.0f);
  EXPECT_EQ(capped.sample->ranges[0], 1.0f);
  EXPECT_FALSE(IsReturn(capped.sample->ranges[2]));
}

TEST(LcmInputDecodeTest, BotPoseGivesPositionAndYaw) {
  for (double yaw : {0.0, 0.7, -2.5, M_PI - 1e-9}) {
    const auto bytes = Encoded(BotPose(1.5, -2.0, yaw));
    const Decoded<OdometrySample> d =
        DecodeOdometryMessage(OdometryMessageType::kBotPose, bytes, kArrival);
    ASSERT_TRUE(d.sample) << d.error;
    EXPECT_EQ(d.sample->stamp, kArrival);
    EXPECT_EQ(d.sample->pose.x, 1.5);
    EXPECT_EQ(d.sample->pose.y, -2.0);
    EXPECT_NEAR(d.sample->pose.theta, yaw, 1e-9);
  }
}

TEST(LcmInputDecodeTest, YawOfATiltedUnnormalisedQuaternion) {
  // A yaw of 0.6 then a roll of 0.3 (z-y-x order), scaled by 3: the yaw is 0.6.
  const double cy = std::cos(0.3), sy = std::sin(0.3), cr = std::cos(0.15), sr = std::sin(0.15);
  const double w = cy * cr, x = cy * sr, y = sy * sr, z = sy * cr;
  EXPECT_NEAR(YawOfQuaternion(3 * w, 3 * x, 3 * y, 3 * z), 0.6, 1e-12);
  EXPECT_NEAR(YawOfQuaternion(0, 0, 0, 1), M_PI, 1e-12);
}

TEST(LcmInputDecodeTest, AtlasOdometryBytesStampedAtArrival) {
  const OdometrySample in{FromSeconds(3), Pose2{1, 2, -0.5}, 12.0, 13.0, 0.5, 0.1};
  const auto bytes = Encoded(ToOdometryMessage(in));
  const Decoded<OdometrySample> d =
      DecodeOdometryMessage(OdometryMessageType::kOdometry, bytes, kArrival);
  ASSERT_TRUE(d.sample) << d.error;
  EXPECT_EQ(d.sample->stamp, kArrival);
  EXPECT_EQ(d.sample->pose.y, 2.0);
  EXPECT_EQ(d.sample->pose.theta, -0.5);
  EXPECT_EQ(d.sample->left_m, 12.0);
}

TEST(LcmInputDecodeTest, AnotherTypeOnTheChannelIsAnErrorNamingTheKey) {
  const auto pose = Encoded(BotPose(0, 0, 0));
  const Decoded<OdometrySample> o =
      DecodeOdometryMessage(OdometryMessageType::kOdometry, pose, kArrival);
  EXPECT_FALSE(o.sample);
  EXPECT_NE(o.error.find("not a atlasd.odometry_t"), std::string::npos) << o.error;
  EXPECT_NE(o.error.find("input.odometry_type"), std::string::npos) << o.error;
  const auto lidar = Encoded(Lidar({1.0f}));
  const Decoded<LaserScan> l =
      DecodeLaserMessage(LaserMessageType::kLaserScan, lidar, kSetup, kArrival);
  EXPECT_FALSE(l.sample);
  EXPECT_NE(l.error.find("input.laser_type"), std::string::npos) << l.error;
}

TEST(LcmInputDecodeTest, DamagedBytesAreErrorsNeverAllocations) {
  std::vector<uint8_t> bytes = Encoded(Lidar({1.0f, 2.0f}));
  // nranges (after the fingerprint and utime) says two billion beams.
  bytes[16] = 0x7f;
  EXPECT_FALSE(DecodeLaserMessage(LaserMessageType::kPlanarLidar, bytes, kSetup, kArrival).sample);
  bytes[16] = 0xff;  // negative
  EXPECT_FALSE(DecodeLaserMessage(LaserMessageType::kPlanarLidar, bytes, kSetup, kArrival).sample);
  const std::vector<uint8_t> good = Encoded(Lidar({1.0f, 2.0f}));
  for (size_t n = 0; n < good.size(); ++n) {  // every truncation
    const std::span<const uint8_t> cut(good.data(), n);
    EXPECT_FALSE(DecodeLaserMessage(LaserMessageType::kPlanarLidar, cut, kSetup, kArrival).sample)
        << n;
  }
  const std::vector<uint8_t> none;
  EXPECT_FALSE(DecodeOdometryMessage(OdometryMessageType::kBotPose, none, kArrival).sample);
}

TEST(LcmInputDecodeTest, MessagesNoScanOrPoseCanHoldAreErrors) {
  EXPECT_NE(FromPlanarLidar(Lidar({}), kSetup, kArrival).error, "");
  bot_core::planar_lidar_t zero_step = Lidar({1.0f});
  zero_step.radstep = 0.0f;
  EXPECT_NE(FromPlanarLidar(zero_step, kSetup, kArrival).error, "");
  bot_core::planar_lidar_t nan_start = Lidar({1.0f});
  nan_start.rad0 = NAN;
  EXPECT_NE(FromPlanarLidar(nan_start, kSetup, kArrival).error, "");
  bot_core::pose_t no_rotation = BotPose(1, 1, 0);
  no_rotation.orientation[0] = 0;
  EXPECT_NE(FromBotPose(no_rotation, kArrival).error, "");
  bot_core::pose_t inf = BotPose(INFINITY, 1, 0);
  EXPECT_NE(FromBotPose(inf, kArrival).error, "");
  atlasd::odometry_t odo{};
  odo.theta = NAN;
  EXPECT_NE(FromAtlasOdometry(odo, kArrival).error, "");
  atlasd::laser_scan_t scan{};
  scan.num_ranges = 1;
  scan.ranges = {1.0f};
  scan.angle_increment = 0.1f;
  scan.max_range = 0.0f;
  EXPECT_NE(FromAtlasLaserScan(scan, kArrival).error, "");
  scan.max_range = 8.0f;
  EXPECT_EQ(FromAtlasLaserScan(scan, kArrival).error, "");
}

// LCM's receive time moves onto the monotonic clock by the clocks' offset; a time the clocks
// cannot place (after now, over a second old, unset) is now.
TEST(LcmInputDecodeTest, ReceiveTimeMovesOntoTheMonotonicClock) {
  const Time now = FromSeconds(500.0);
  const int64_t realtime_now_us = 1'700'000'000'000'000;
  EXPECT_EQ(ArrivalOnMonotonicClock(realtime_now_us - 3000, realtime_now_us, now),
            now - std::chrono::milliseconds(3));
  EXPECT_EQ(ArrivalOnMonotonicClock(realtime_now_us, realtime_now_us, now), now);
  EXPECT_EQ(ArrivalOnMonotonicClock(realtime_now_us - 999'999, realtime_now_us, now),
            now - std::chrono::microseconds(999'999));
  EXPECT_EQ(ArrivalOnMonotonicClock(realtime_now_us + 5, realtime_now_us, now), now);
  EXPECT_EQ(ArrivalOnMonotonicClock(realtime_now_us - 1'000'001, realtime_now_us, now), now);
  EXPECT_EQ(ArrivalOnMonotonicClock(0, realtime_now_us, now), now);
}

}  // namespace
}  // namespace atlas
