#include "formats/trajectory_tsv.h"

#include <gtest/gtest.h>

#include <numbers>

namespace atlas::formats {
namespace {

TEST(TrajectoryTsv, RoundTrips) {
  const std::vector<FramePoseRow> rows = {{FromSeconds(10.5), 0, Pose2{1, 2, 0.5}, 0},
                                          {FromSeconds(11.25), 3, Pose2{-1, 0.125, -3.0}, 0}};
  const std::string text = FormatTrajectoryTsv(rows, "trajectory: timestamp frame x y theta");
  EXPECT_EQ(text,
            "# trajectory: timestamp frame x y theta\n10.500000\t0\t1.000000\t2.000000\t0.500000\n"
            "11.250000\t3\t-1.000000\t0.125000\t-3.000000\n");
  std::vector<FramePoseRow> read;
  ASSERT_EQ(ParseTrajectoryTsv(text, "t.tsv", &read), "");
  ASSERT_EQ(read.size(), 2u);
  EXPECT_EQ(read[1].stamp, rows[1].stamp);
  EXPECT_EQ(read[1].frame, 3);
  EXPECT_EQ(read[1].pose.y, 0.125);
  EXPECT_EQ(read[1].line, 3);
  EXPECT_EQ(FormatTrajectoryTsv(read, "trajectory: timestamp frame x y theta"), text);
}

// The rules every reader of trajectory.tsv shares (docs/formats.md): theta is wrapped, a stamp
// may not repeat, a frame is an integer >= 0.
TEST(TrajectoryTsv, WrapsThetaAndRefusesRepeatedStampsAndBadFrames) {
  std::vector<FramePoseRow> read;
  ASSERT_EQ(ParseTrajectoryTsv("1 0 0 0 7.0\n", "t.tsv", &read), "");
  EXPECT_NEAR(read[0].pose.theta, 7.0 - 2 * std::numbers::pi, 1e-12);
  EXPECT_EQ(ParseTrajectoryTsv("1 0 0 0 0\n1 1 0 0 0\n", "t.tsv", &read)
                .rfind("t.tsv:2: timestamp 1.000000 repeats line 1", 0),
            0u);
  EXPECT_EQ(ParseTrajectoryTsv("1.0 -3 0 0 0\n", "t.tsv", &read),
            "t.tsv:1: field 2 is '-3', not a frame id (an integer 0..1e8)");
  EXPECT_EQ(ParseTrajectoryTsv("1.0 1.5 0 0 0\n", "t.tsv", &read).rfind("t.tsv:1: field 2 ", 0),
            0u);
  EXPECT_EQ(ParseTrajectoryTsv("1e300 0 0 0 0\n", "t.tsv", &read).rfind("t.tsv:1: field 1 (a ", 0),
            0u);
}

}  // namespace
}  // namespace atlas::formats
