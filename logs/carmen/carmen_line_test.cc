#include "logs/carmen/carmen_line.h"

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

namespace atlas::carmen {
namespace {

constexpr double kPi = std::numbers::pi;

TEST(CarmenLineTest, ParsesFlaser) {
  const ParsedLine p =
      ParseLine("FLASER 3 1.5 81.91 2.25 0.1 0.2 0.3 1.1 2.2 -3.3 1134864629.895182 b21 0.0863");
  ASSERT_TRUE(p.ok()) << p.reason;
  EXPECT_EQ(p.kind, LineKind::kLaser);
  EXPECT_EQ(p.laser.message, "FLASER");
  ASSERT_EQ(p.laser.ranges.size(), 3u);
  EXPECT_FLOAT_EQ(p.laser.ranges[0], 1.5f);
  EXPECT_FLOAT_EQ(p.laser.ranges[1], 81.91f);
  EXPECT_FLOAT_EQ(p.laser.ranges[2], 2.25f);
  ASSERT_TRUE(p.laser.laser_pose.has_value());
  ASSERT_TRUE(p.laser.odometry_pose.has_value());
  EXPECT_DOUBLE_EQ(p.laser.laser_pose->x, 0.1);
  EXPECT_DOUBLE_EQ(p.laser.laser_pose->theta, 0.3);
  EXPECT_DOUBLE_EQ(p.laser.odometry_pose->x, 1.1);
  EXPECT_DOUBLE_EQ(p.laser.odometry_pose->y, 2.2);
  EXPECT_DOUBLE_EQ(p.laser.odometry_pose->theta, -3.3);
  EXPECT_DOUBLE_EQ(p.laser.ipc_timestamp, 1134864629.895182);
  EXPECT_EQ(p.laser.hostname, "b21");
  EXPECT_DOUBLE_EQ(p.laser.logger_timestamp, 0.0863);
  EXPECT_DOUBLE_EQ(p.laser.start_angle, -kPi / 2);
}

TEST(CarmenLineTest, FlaserBeamGeometryFollowsCarmen) {
  EXPECT_DOUBLE_EQ(GuessFlaserAngleIncrement(361), kPi / 360);
  EXPECT_DOUBLE_EQ(GuessFlaserAngleIncrement(360), kPi / 360);
  EXPECT_DOUBLE_EQ(GuessFlaserAngleIncrement(180), kPi / 180);
  EXPECT_DOUBLE_EQ(GuessFlaserAngleIncrement(181), kPi / 180);
  // 361 beams from -90 deg end at +90 deg.
  EXPECT_NEAR(-kPi / 2 + 360 * GuessFlaserAngleIncrement(361), kPi / 2, 1e-12);
  EXPECT_NEAR(GuessFlaserAngleIncrement(11), kPi / 10, 1e-12);
}

TEST(CarmenLineTest, ParsesOdom) {
  const ParsedLine p =
      ParseLine("ODOM 0.000485382 6.20016e-05 -0.001534 0.1 0.2 0 0.227623 pippo 0.227623\r");
  ASSERT_TRUE(p.ok()) << p.reason;
  EXPECT_EQ(p.kind, LineKind::kOdometry);
  EXPECT_DOUBLE_EQ(p.odometry.pose.x, 0.000485382);
  EXPECT_DOUBLE_EQ(p.odometry.pose.y, 6.20016e-05);
  EXPECT_DOUBLE_EQ(p.odometry.pose.theta, -0.001534);
  EXPECT_DOUBLE_EQ(p.odometry.tv, 0.1);
  EXPECT_DOUBLE_EQ(p.odometry.rv, 0.2);
  EXPECT_DOUBLE_EQ(p.odometry.ipc_timestamp, 0.227623);
  EXPECT_EQ(p.odometry.hostname, "pippo");
}

TEST(CarmenLineTest, ParsesRawlaserWithRemissions) {
  const ParsedLine p = ParseLine(
      "RAWLASER3 0 -1.5708 3.14159 0.0174533 81.9 0.01 0 4 1 2 3 4 2 0.5 0.6 12.5 host 12.6");
  ASSERT_TRUE(p.ok()) << p.reason;
  EXPECT_EQ(p.kind, LineKind::kLaser);
  EXPECT_EQ(p.laser.laser_id, 3);
  EXPECT_DOUBLE_EQ(p.laser.start_angle, -1.5708);
  EXPECT_DOUBLE_EQ(p.laser.fov, 3.14159);
  EXPECT_DOUBLE_EQ(p.laser.angular_resolution, 0.0174533);
  EXPECT_DOUBLE_EQ(p.laser.max_range, 81.9);
  ASSERT_EQ(p.laser.ranges.size(), 4u);
  EXPECT_FLOAT_EQ(p.laser.ranges[3], 4.0f);
  EXPECT_FALSE(p.laser.laser_pose.has_value());
  EXPECT_DOUBLE_EQ(p.laser.ipc_timestamp, 12.5);
}

TEST(CarmenLineTest, ParsesRobotlaser1) {
  const ParsedLine p = ParseLine(
      "ROBOTLASER1 0 -1.5708 3.14159 0.0174533 50 0.01 0 2 1.25 2.5 0 "
      "1.1 2.1 0.3 1 2 0.3 0.5 0.1 0.3 0.2 0.4 99.5 host 99.6");
  ASSERT_TRUE(p.ok()) << p.reason;
  EXPECT_EQ(p.kind, LineKind::kLaser);
  ASSERT_EQ(p.laser.ranges.size(), 2u);
  EXPECT_DOUBLE_EQ(p.laser.laser_pose->x, 1.1);
  EXPECT_DOUBLE_EQ(p.laser.odometry_pose->x, 1.0);
  EXPECT_DOUBLE_EQ(p.laser.max_range, 50.0);
  EXPECT_DOUBLE_EQ(p.laser.ipc_timestamp, 99.5);
}

TEST(CarmenLineTest, IgnoresOtherMessagesCommentsAndBlanks) {
  EXPECT_EQ(ParseLine("NEFF 30").kind, LineKind::kIgnored);
  EXPECT_TRUE(ParseLine("NEFF 30").ok());
  EXPECT_EQ(ParseLine("PARAM robot_use_laser on nohost 0").message, "PARAM");
  EXPECT_TRUE(ParseLine("TRUTH 1 2 3 4 5 6 7 h 8").ok());
  EXPECT_TRUE(ParseLine("# FLASER num_readings").ok());
  EXPECT_EQ(ParseLine("# FLASER num_readings").message, "");
  EXPECT_TRUE(ParseLine("#PARAM x").ok());
  EXPECT_TRUE(ParseLine("").ok());
  EXPECT_TRUE(ParseLine("   \t ").ok());
}

TEST(CarmenLineTest, RejectsMalformedLinesWithReasons) {
  ParsedLine p = ParseLine("FLASER 3 1.5 2.5 0.1 0.2 0.3 1.1 2.2 -3.3 1.0 b21 0.08");
  // One range short: every later field shifts and the hostname lands on ipc_timestamp.
  EXPECT_EQ(p.error, LineError::kBadNumber);
  EXPECT_NE(p.reason.find("ipc_timestamp) is 'b21'"), std::string::npos) << p.reason;

  p = ParseLine("FLASER 3 1.5 2.x 2.5 0.1 0.2 0.3 1.1 2.2 -3.3 1.0 b21 0.08");
  EXPECT_EQ(p.error, LineError::kBadNumber);
  EXPECT_NE(p.reason.find("'2.x'"), std::string::npos) << p.reason;
  EXPECT_NE(p.reason.find("field 4"), std::string::npos) << p.reason;

  p = ParseLine("FLASER 3 1.5 2.5 2.5 0.1 0.2 0.3 1.1 2.2 -3.3 1.0 b21 0.08 extra");
  EXPECT_EQ(p.error, LineError::kExtraFields);

  p = ParseLine("FLASER -3 1.0 b21 0.08");
  EXPECT_EQ(p.error, LineError::kBadCount);
  p = ParseLine("FLASER 2.5 1 2");
  EXPECT_EQ(p.error, LineError::kBadCount);
  p = ParseLine("FLASER 1000000000 1 2");
  EXPECT_EQ(p.error, LineError::kBadCount);

  p = ParseLine("FLASER 2 1.5 -2.5 0.1 0.2 0.3 1.1 2.2 -3.3 1.0 b21 0.08");
  EXPECT_EQ(p.error, LineError::kBadRange);

  p = ParseLine("ODOM 1 2 nan 0 0 0 1.0 h 1.0");
  EXPECT_EQ(p.error, LineError::kBadNumber);
  p = ParseLine("ODOM 1 2 3 0 0 0 1.0 h");
  EXPECT_EQ(p.error, LineError::kMissingFields);

  p = ParseLine("FLA$ER 2 1 2");
  EXPECT_EQ(p.error, LineError::kBadMessageName);
  p = ParseLine("1.5 2.5 3.5");
  EXPECT_EQ(p.error, LineError::kBadMessageName);
}

TEST(CarmenLineTest, ErrorMessagesQuoteBinaryGarbageSafely) {
  const ParsedLine p = ParseLine(std::string("ODOM 1 2 \x01\xff") + std::string(100, 'z'));
  EXPECT_EQ(p.error, LineError::kBadNumber);
  EXPECT_NE(p.reason.find("'\\x01\\xffzzz"), std::string::npos) << p.reason;
  EXPECT_NE(p.reason.find("zzz'..."), std::string::npos) << p.reason;
  EXPECT_LT(p.reason.size(), 120u);
}

TEST(CarmenLineTest, TruncatedPrefixesOfAValidLineNeverParse) {
  const std::string good = "FLASER 2 1.5 2.5 0.1 0.2 0.3 1.1 2.2 -3.3 1.0 b21 0.08";
  ASSERT_TRUE(ParseLine(good).ok());
  int rejected = 0, cuts = 0;
  for (size_t cut = 8; cut < good.size(); ++cut) {
    if (good[cut] != ' ') continue;  // cut at a field boundary
    ++cuts;
    if (!ParseLine(good.substr(0, cut)).ok()) ++rejected;
  }
  EXPECT_GT(cuts, 5);
  EXPECT_EQ(rejected, cuts);
}

}  // namespace
}  // namespace atlas::carmen
