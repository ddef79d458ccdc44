#include "sim/carmen_writer.h"

#include <gtest/gtest.h>

#include "logs/carmen/carmen_line.h"

namespace atlas::sim {
namespace {

std::string_view OneLine(const std::string& s) {
  EXPECT_FALSE(s.empty());
  EXPECT_EQ(s.back(), '\n');
  return std::string_view(s).substr(0, s.size() - 1);
}

TEST(CarmenWriter, FlaserLineReadsBackWithTheProjectReader) {
  LaserScan scan;
  scan.stamp = FromSeconds(1234.5);
  scan.ranges = {1.0f, 2.5f, kNoReturn, 0.0f, 29.9994f};
  scan.sensor_pose = Pose2{0.1, 0.0, 0.0};
  std::string s;
  AppendFlaserLine(&s, scan, Pose2{-3.25, 4.0, -1.5});
  const carmen::ParsedLine p = carmen::ParseLine(OneLine(s));
  ASSERT_TRUE(p.ok()) << p.reason << " in: " << s;
  ASSERT_EQ(p.kind, carmen::LineKind::kLaser);
  ASSERT_EQ(p.laser.ranges.size(), 5u);
  EXPECT_FLOAT_EQ(p.laser.ranges[1], 2.5f);
  EXPECT_FLOAT_EQ(p.laser.ranges[2], 81.91f);  // the SICK no-return code
  EXPECT_FLOAT_EQ(p.laser.ranges[4], 29.999f);
  ASSERT_TRUE(p.laser.odometry_pose && p.laser.laser_pose);
  EXPECT_NEAR(p.laser.odometry_pose->x, -3.25, 1e-9);
  EXPECT_NEAR(p.laser.odometry_pose->theta, -1.5, 1e-9);
  // Laser pose = odometry (+) mount: 0.1 m ahead along heading -1.5.
  EXPECT_NEAR(p.laser.laser_pose->x, -3.25 + 0.1 * std::cos(-1.5), 1e-4);
  EXPECT_NEAR(p.laser.laser_pose->y, 4.0 + 0.1 * std::sin(-1.5), 1e-4);
  EXPECT_NEAR(p.laser.ipc_timestamp, 1234.5, 1e-9);
  EXPECT_EQ(p.laser.hostname, "atlas-sim");
}

TEST(CarmenWriter, OdomLineReadsBack) {
  std::string s;
  AppendOdomLine(&s, OdometrySample{FromSeconds(10.02), Pose2{1e-6, -0.00004, 3.14159}}, 0.8,
                 -0.25);
  EXPECT_EQ(s, "ODOM 0.0000 0.0000 3.14159 0.8000 -0.2500 0.0 10.020000 atlas-sim 10.020000\n");
  const carmen::ParsedLine p = carmen::ParseLine(OneLine(s));
  ASSERT_TRUE(p.ok()) << p.reason;
  EXPECT_EQ(p.kind, carmen::LineKind::kOdometry);
  EXPECT_NEAR(p.odometry.tv, 0.8, 1e-12);
}

TEST(CarmenWriter, SonarLineIsProjectSpecificAndIgnoredByCarmenReaders) {
  SonarReading r;
  r.stamp = FromSeconds(5.0);
  r.returns = {{3, 1.25f}, {4, kNoReturn}};
  std::string s;
  AppendSonarLine(&s, r, Pose2{1, 2, 0.5});
  EXPECT_EQ(s, "SONAR 2 3 1.250 4 -1.000 1.0000 2.0000 0.50000 5.000000 atlas-sim 5.000000\n");
  const carmen::ParsedLine p = carmen::ParseLine(OneLine(s));
  EXPECT_TRUE(p.ok());
  EXPECT_EQ(p.kind, carmen::LineKind::kIgnored);
}

TEST(CarmenWriter, TruthRowAndRounding) {
  std::string s;
  AppendTruthRow(&s, TruthSample{FromSeconds(1.5), Pose2{-0.000004, 12.345675, -3.0}});
  EXPECT_EQ(s, "1.500000\t0.00000\t12.34568\t-3.000000\n");
}

}  // namespace
}  // namespace atlas::sim
