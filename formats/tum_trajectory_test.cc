#include "formats/tum_trajectory.h"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <numbers>

namespace atlas::formats {
namespace {

using ::testing::HasSubstr;

TEST(TumTrajectory, WritesPlanarQuaternionsAndReadsThemBack) {
  const std::vector<eval::TimedPose> poses = {
      {FromSeconds(10.5), Pose2{1, 2, 0}},
      {FromSeconds(11.0), Pose2{-1, 0.5, std::numbers::pi / 2}},
      {FromSeconds(11.5), Pose2{0, 0, -3.0}}};
  const std::string text = FormatTumTrajectory(poses, "tum");
  EXPECT_THAT(text,
              HasSubstr("# tum\n10.500000 1.000000 2.000000 0 0 0 0.000000000 1.000000000\n"));
  EXPECT_THAT(text, HasSubstr("11.000000 -1.000000 0.500000 0 0 0 0.707106781 0.707106781\n"));
  std::vector<eval::TimedPose> read;
  ASSERT_EQ(ParseTumTrajectory(text, "t.tum", &read), "");
  ASSERT_EQ(read.size(), 3u);
  for (size_t i = 0; i < poses.size(); ++i) {
    EXPECT_EQ(read[i].stamp, poses[i].stamp);
    EXPECT_NEAR(read[i].pose.x, poses[i].pose.x, 1e-9);
    EXPECT_NEAR(read[i].pose.theta, poses[i].pose.theta, 1e-8);
  }
}

TEST(TumTrajectory, RefusesNonUnitAndNonPlanarPoses) {
  std::vector<eval::TimedPose> read;
  EXPECT_THAT(ParseTumTrajectory("1 0 0 0 0 0 0.5 0.5\n", "t.tum", &read),
              HasSubstr("t.tum:1: the quaternion (fields 5-8) has norm"));
  EXPECT_EQ(ParseTumTrajectory("1 0 0 0.5 0 0 0 1\n", "t.tum", &read),
            "t.tum:1: the pose is not in the plane (tz, qx and qy must be 0)");
  EXPECT_THAT(ParseTumTrajectory("1 0 0 0 0 0 1\n", "t.tum", &read),
              HasSubstr("t.tum:1: expected 8 fields"));
}

}  // namespace
}  // namespace atlas::formats
