// The simulator's CARMEN writer (sim/carmen_writer.h) and this reader agree: a simulated
// run written as log lines reads back as the same events.

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <string>

#include "logs/carmen/carmen_log.h"
#include "sim/carmen_writer.h"

namespace atlas::carmen {
namespace {

TEST(SimLogRoundTripTest, WrittenRunReadsBack) {
  std::string text;
  LaserScan scan;
  scan.stamp = FromSeconds(1000.1);
  scan.angle_min = static_cast<float>(-std::numbers::pi / 2);
  scan.angle_increment = static_cast<float>(std::numbers::pi / 180);
  scan.max_range = 30.0f;
  for (int i = 0; i < 181; ++i) scan.ranges.push_back(i == 7 ? kNoReturn : 0.5f + 0.01f * i);
  const Pose2 odometry{1.25, -0.5, 0.3};
  sim::AppendOdomLine(&text, OdometrySample{FromSeconds(1000.0), Pose2{1.0, -0.5, 0.25}}, 0.5, 0.1);
  sim::AppendFlaserLine(&text, scan, odometry);
  SonarReading sonar;
  sonar.stamp = FromSeconds(1000.15);
  sonar.returns = {{0, 1.5f}, {3, kNoReturn}};
  sim::AppendSonarLine(&text, sonar, odometry);
  sim::AppendOdomLine(&text, OdometrySample{FromSeconds(1000.2), Pose2{1.5, -0.5, 0.35}}, 0.5, 0.1);

  CarmenLogBuilder b(CarmenLogOptions{}, "sim");
  int64_t line = 0;
  size_t pos = 0;
  while (pos < text.size()) {
    const size_t end = text.find('\n', pos);
    ASSERT_NE(end, std::string::npos);
    ASSERT_TRUE(b.AddLine(++line, std::string_view(text).substr(pos, end - pos))) << b.error();
    pos = end + 1;
  }
  const CarmenLog log = b.Finish();
  EXPECT_EQ(line, 4);
  EXPECT_EQ(log.lines_by_message.at("SONAR"), 1);  // ignored, counted
  EXPECT_EQ(log.odometry_events, 2);               // from ODOM lines, not the FLASER fields
  ASSERT_EQ(log.events.size(), 3u);
  const auto& o = std::get<OdometrySample>(log.events[0].event);
  EXPECT_EQ(o.stamp, FromSeconds(1000.0));
  EXPECT_NEAR(o.pose.x, 1.0, 1e-4);
  const auto& s = std::get<LaserScan>(log.events[1].event);
  EXPECT_EQ(s.stamp, FromSeconds(1000.1));
  ASSERT_EQ(s.ranges.size(), 181u);
  EXPECT_NEAR(s.angle_min, scan.angle_min, 1e-6);
  EXPECT_NEAR(s.angle_increment, scan.angle_increment, 1e-7);
  for (int i = 0; i < 181; ++i) {
    if (i == 7) {
      EXPECT_FALSE(IsReturn(s.ranges[i]));
    } else {
      EXPECT_NEAR(s.ranges[i], scan.ranges[i], 1e-3) << i;
    }
  }
  ASSERT_TRUE(log.events[1].odometry_pose.has_value());
  EXPECT_NEAR(log.events[1].odometry_pose->x, 1.25, 1e-4);
  EXPECT_NEAR(log.events[1].odometry_pose->theta, 0.3, 1e-5);
  EXPECT_NEAR(s.sensor_pose.x, 0.0, 1e-9);  // laser at the robot's origin
}

}  // namespace
}  // namespace atlas::carmen
