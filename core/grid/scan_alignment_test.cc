#include "core/grid/scan_alignment.h"

#include <gtest/gtest.h>

#include <Eigen/Eigenvalues>
#include <cmath>

#include "core/testing/grid_scenes.h"

namespace atlas {
namespace {

TEST(ScanAligner, RecoversAKnownOffsetInARoom) {
  const GridOptions o;
  const std::vector<sim::Wall> walls = RoomWalls();
  const ProbabilityGrid grid =
      ScannedGrid(walls, {Pose2{0, 0, 0}, Pose2{-3, -2, 1.0}, Pose2{3, 2, -2.0}}, o);
  ScanAligner aligner(o.alignment);
  const Pose2 truths[] = {{0.5, -0.4, 0.3}, {-2.0, 1.0, -1.2}, {3.5, -1.5, 2.5}};
  const Pose2 errors[] = {{0.09, -0.07, 0.05}, {-0.12, 0.1, -0.08}, {0.0, 0.13, 0.02}};
  for (int k = 0; k < 3; ++k) {
    const std::vector<Vec2> points = ScanPoints(walls, truths[k], o, 10 + k);
    const Pose2 initial{truths[k].x + errors[k].x, truths[k].y + errors[k].y,
                        truths[k].theta + errors[k].theta};
    const AlignmentResult r = aligner.Align(grid, points, initial);
    ASSERT_EQ(r.outcome, AlignmentOutcome::kAligned) << k << " " << ToString(r.outcome);
    // Within half a cell and 0.6 degrees of the truth.
    EXPECT_NEAR(r.pose.mean.x, truths[k].x, 0.025) << k;
    EXPECT_NEAR(r.pose.mean.y, truths[k].y, 0.025) << k;
    EXPECT_NEAR(WrapAngle(r.pose.mean.theta - truths[k].theta), 0.0, 0.01) << k;
    EXPECT_GT(r.score, 0.4);
    EXPECT_GE(r.score, r.correlative_score - 0.05);
    EXPECT_EQ(r.unconstrained, 0);
    // A covariance from the match: small, positive definite, consistent with the error.
    const Eigen::SelfAdjointEigenSolver<Mat3> eigen(r.pose.cov);
    EXPECT_GT(eigen.eigenvalues()(0), 0.0);
    EXPECT_LT(std::sqrt(r.pose.cov(0, 0)), 0.02);
    EXPECT_LT(std::sqrt(r.pose.cov(2, 2)), 0.01);
  }
}

TEST(ScanAligner, ReportsTheCorridorsLengthAsUnconstrained) {
  const GridOptions o;
  const std::vector<sim::Wall> walls = LongCorridorWalls();
  std::vector<Pose2> poses;
  for (double x = -4.0; x <= 4.0; x += 2.0) poses.push_back(Pose2{x, 0.1, 0.0});
  const ProbabilityGrid grid = ScannedGrid(walls, poses, o);
  ScanAligner aligner(o.alignment);
  const Pose2 truth{0.3, -0.2, 0.05};
  const std::vector<Vec2> points = ScanPoints(walls, truth, o);
  const AlignmentResult r = aligner.Align(grid, points, Pose2{0.35, -0.15, 0.08});
  ASSERT_EQ(r.outcome, AlignmentOutcome::kUnconstrained);
  ASSERT_EQ(r.unconstrained, 1);
  // The free direction is the corridor's axis, x.
  EXPECT_GT(std::abs(r.unconstrained_directions(0, 0)), 0.95);
  EXPECT_GT(r.pose.cov(0, 0), 1.0);
  // Across the corridor and in heading the grid fixes the pose.
  EXPECT_NEAR(r.pose.mean.y, truth.y, 0.01);
  EXPECT_NEAR(WrapAngle(r.pose.mean.theta - truth.theta), 0.0, 0.005);
  // Given x, y and the heading are fixed by the information (the unconstrained direction has
  // a little heading in it, so the covariance's marginal heading variance is not small).
  const Eigen::Matrix2d given_x = r.information.block<2, 2>(1, 1).inverse();
  EXPECT_LT(std::sqrt(given_x(0, 0)), 0.02);
  EXPECT_LT(std::sqrt(given_x(1, 1)), 0.01);
}

TEST(ScanAligner, RefusesTooFewPointsAndAnUnknownGrid) {
  const GridOptions o;
  ScanAligner aligner(o.alignment);
  const ProbabilityGrid empty(o.grid, Vec2(-5, -5), Vec2(5, 5));
  const std::vector<Vec2> points = ScanPoints(RoomWalls(), Pose2{}, o);
  AlignmentResult r = aligner.Align(empty, points, Pose2{0.1, 0.2, 0.3});
  EXPECT_EQ(r.outcome, AlignmentOutcome::kLowScore);
  EXPECT_EQ(r.pose.mean.x, 0.1);
  r = aligner.Align(empty, std::vector<Vec2>(points.begin(), points.begin() + 5), Pose2{});
  EXPECT_EQ(r.outcome, AlignmentOutcome::kTooFewPoints);
}

}  // namespace
}  // namespace atlas
