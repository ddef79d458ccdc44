#include "formats/pose_file.h"

#include <gtest/gtest.h>

#include <numbers>

namespace atlas::formats {
namespace {

TEST(PoseFile, RoundTrips) {
  const std::vector<eval::TimedPose> poses = {{FromSeconds(1134864629.895182), Pose2{1.5, -2, 3.0}},
                                              {FromSeconds(0.25), Pose2{0, 0, -0.5}}};
  const std::string text = FormatPoseRows(poses, "a comment\ntimestamp x y theta");
  EXPECT_EQ(text,
            "# a comment\n# timestamp x y theta\n1134864629.895182\t1.500000\t-2.000000\t"
            "3.000000\n0.250000\t0.000000\t0.000000\t-0.500000\n");
  const PoseRows read = ParsePoseRows(text, "p.tsv");
  ASSERT_EQ(read.error, "");
  ASSERT_EQ(read.poses.size(), 2u);  // file order
  EXPECT_EQ(read.lines, (std::vector<int64_t>{3, 4}));
  for (size_t i = 0; i < poses.size(); ++i) {
    EXPECT_EQ(read.poses[i].stamp, poses[i].stamp);
    EXPECT_EQ(read.poses[i].pose.x, poses[i].pose.x);
    EXPECT_EQ(read.poses[i].pose.theta, poses[i].pose.theta);
  }
  EXPECT_EQ(FormatPoseRows(read.poses, "a comment\ntimestamp x y theta"), text);
}

TEST(PoseFile, RefusesBadRowsWithFileAndLine) {
  EXPECT_EQ(ParsePoseRows("1 2 3 4\n1.5 2 x 4\n", "t.tsv").error,
            "t.tsv:2: field 3 is 'x', not a number");
  EXPECT_EQ(ParsePoseRows("# c\n1 2 3\n", "t.tsv").error,
            "t.tsv:2: expected 4 fields (timestamp x y theta), found 3");
  EXPECT_EQ(ParsePoseRows("1 0 0 1e9\n", "t.tsv").error.rfind("t.tsv:1: field 4 is ", 0), 0u);
  EXPECT_EQ(ParsePoseRows("# h\n1 0 0 0\n2 0 0 0\n1.0000000001 5 0 0\n", "t.tsv").error,
            "t.tsv:4: timestamp 1.000000 repeats line 2 (one pose per stamp: remove one of the two "
            "rows)");
  const PoseRows empty = ParsePoseRows("# only a comment\n", "t.tsv");
  EXPECT_EQ(empty.error, "");
  EXPECT_TRUE(empty.poses.empty());
  EXPECT_NEAR(ParsePoseRows("1 0 0 3.5\n", "t").poses[0].pose.theta, 3.5 - 2 * std::numbers::pi,
              1e-12);
}

}  // namespace
}  // namespace atlas::formats
