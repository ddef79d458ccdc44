#include "core/scanmatch/scan_matcher.h"

#include <gtest/gtest.h>

#include <Eigen/Cholesky>
#include <cmath>
#include <limits>
#include <random>

#include "core/testing/degrees.h"
#include "core/testing/fake_wall_scanner.h"
#include "sim/corridor.h"

namespace atlas {
namespace {

FakeLaserOptions Laser() {
  FakeLaserOptions o;
  o.beams = 361;
  o.max_range = 30.0;
  o.range_sigma = 0.01;
  o.sensor_pose = Pose2{0.1, 0.0, 0.0};
  return o;
}

ScanMatchOptions Options() {
  ScanMatchOptions o;
  o.enabled = true;
  return o;
}

UncertainPose Prior(const Pose2& mean, double sxy, double stheta) {
  UncertainPose p;
  p.mean = mean;
  p.cov = Vec3(sxy * sxy, sxy * sxy, stheta * stheta).asDiagonal();
  return p;
}

TEST(ScanMatcher, RecoversTheMotionFromAWrongOdometryHeading) {
  FakeWallScanner laser(sim::CorridorWalls(), Laser(), 7);
  const Pose2 a{6.0, 1.0, 0.1}, b{6.25, 1.05, 0.25};
  const Pose2 truth = Between(a, b);
  ScanMatchOptions options = Options();
  options.heading_search = 20.0 * kDeg;
  ScanMatcher matcher(options);
  matcher.SetReference(laser.Scan(a));
  // The wheels say the robot turned 12 degrees less and rolled 5 cm further than it did.
  const Pose2 odometry{truth.x + 0.05, truth.y, truth.theta - 12.0 * kDeg};
  const ScanMatchResult r = matcher.Match(laser.Scan(b), Prior(odometry, 0.05, 5.0 * kDeg));
  ASSERT_EQ(r.outcome, ScanMatchOutcome::kMatched) << ToString(r.outcome);
  // The heading comes from the scans; the 5 cm along the corridor is weakly observed (the end
  // walls are 6 and 24 m away) and the prior keeps part of it.
  EXPECT_NEAR(WrapAngle(r.increment.mean.theta - truth.theta), 0.0, 0.2 * kDeg);
  EXPECT_NEAR(r.increment.mean.y, truth.y, 0.01);
  EXPECT_LT(std::abs(r.increment.mean.x - truth.x), 0.6 * 0.05);
  EXPECT_GT(r.pairs, 100);
  EXPECT_LT(r.increment.cov(2, 2), (0.5 * kDeg) * (0.5 * kDeg));
}

TEST(ScanMatcher, KeepsTheOdometryAlongAFeaturelessCorridor) {
  // Two long parallel walls: the scans fix the heading and the cross-axis offset, not the
  // position along the axis.
  const std::vector<sim::Wall> walls = {{Vec2(-100, -1.2), Vec2(100, -1.2)},
                                        {Vec2(-100, 1.2), Vec2(100, 1.2)}};
  FakeWallScanner laser(walls, Laser(), 3);
  const Pose2 a{0.0, 0.0, 0.0}, b{0.3, 0.02, 0.02};
  const Pose2 truth = Between(a, b);
  ScanMatcher matcher(Options());
  matcher.SetReference(laser.Scan(a));
  const Pose2 odometry{truth.x + 0.04, truth.y - 0.03, truth.theta + 3.0 * kDeg};
  const UncertainPose prior = Prior(odometry, 0.05, 5.0 * kDeg);
  const ScanMatchResult r = matcher.Match(laser.Scan(b), prior);
  ASSERT_EQ(r.outcome, ScanMatchOutcome::kMatched) << ToString(r.outcome);
  // Across the corridor and in heading: the scans.
  EXPECT_NEAR(r.increment.mean.y, truth.y, 0.01);
  EXPECT_NEAR(WrapAngle(r.increment.mean.theta - truth.theta), 0.0, 0.2 * kDeg);
  EXPECT_LT(r.increment.cov(1, 1), 0.1 * prior.cov(1, 1));
  // Along the axis: the odometry, with its variance.
  EXPECT_NEAR(r.increment.mean.x, odometry.x, 0.01);
  EXPECT_GT(r.increment.cov(0, 0), 0.8 * prior.cov(0, 0));
}

TEST(ScanMatcher, CovarianceIsNotOverConfidentOverManyPairs) {
  std::mt19937_64 rng(11);
  std::normal_distribution<double> normal(0.0, 1.0);
  std::uniform_real_distribution<double> along(2.0, 26.0), across(-0.6, 0.6), turn(-0.5, 0.5);
  FakeWallScanner laser(sim::CorridorWalls(), Laser(), 5);
  ScanMatcher matcher(Options());
  const int runs = 200;
  double nees = 0.0, prior_error = 0.0, match_error = 0.0;
  int matched = 0;
  for (int i = 0; i < runs; ++i) {
    const Pose2 a{along(rng), across(rng), turn(rng)};
    const Pose2 truth{0.2 + 0.05 * normal(rng), 0.02 * normal(rng), 0.1 * normal(rng)};
    const Pose2 b = Compose(a, truth);
    matcher.SetReference(laser.Scan(a));
    const double sxy = 0.03, st = 3.0 * kDeg;
    const Pose2 odometry{truth.x + sxy * normal(rng), truth.y + sxy * normal(rng),
                         truth.theta + st * normal(rng)};
    const ScanMatchResult r = matcher.Match(laser.Scan(b), Prior(odometry, sxy, st));
    if (r.outcome != ScanMatchOutcome::kMatched) continue;
    ++matched;
    const Vec3 e(r.increment.mean.x - truth.x, r.increment.mean.y - truth.y,
                 WrapAngle(r.increment.mean.theta - truth.theta));
    nees += e.dot(r.increment.cov.ldlt().solve(e));
    prior_error += std::abs(WrapAngle(odometry.theta - truth.theta));
    match_error += std::abs(e(2));
  }
  ASSERT_GT(matched, runs * 9 / 10);
  nees /= matched;
  // A consistent estimate has NEES 3; the information scale makes it conservative on these
  // exact walls. Over-confidence (NEES above 3 by half) would mislead the maps' gates.
  EXPECT_LT(nees, 4.5);
  EXPECT_GT(nees, 0.05);
  EXPECT_LT(match_error, 0.1 * prior_error);
  std::printf(
      "scan matcher on %d corridor pairs: NEES %.2f, heading error %.3f deg (odometry "
      "%.3f deg)\n",
      matched, nees, match_error / matched / kDeg, prior_error / matched / kDeg);
}

// The wheels report no motion (covariance zero) while the robot turned 15 degrees and rolled
// 0.15 m, as mit-csail's odometry does for up to 0.6 s at a time: the match at the odometry's
// increment pairs too few points; the recovery pass searches the heading with a weak prior.
TEST(ScanMatcher, RecoveryPassFindsATurnTheOdometryMissed) {
  FakeWallScanner laser(sim::CorridorWalls(), Laser(), 4);
  const Pose2 a{8.0, 0.2, 0.3}, b = Compose(a, Pose2{0.15, 0.0, 15.0 * kDeg});
  const Pose2 truth = Between(a, b);
  const LaserScan ref = laser.Scan(a), cur = laser.Scan(b);
  const UncertainPose standing{Pose2{}, Mat3::Zero()};
  ScanMatcher plain(Options());
  plain.SetReference(ref);
  const ScanMatchResult r0 = plain.Match(cur, standing);
  EXPECT_NE(r0.outcome, ScanMatchOutcome::kMatched);
  EXPECT_EQ(r0.increment.mean.theta, 0.0);
  ScanMatchOptions o = Options();
  o.recovery_heading_search = 0.8;
  ASSERT_EQ(o.Validate(), "");
  ScanMatcher recovering(o);
  recovering.SetReference(ref);
  const ScanMatchResult r = recovering.Match(cur, standing);
  ASSERT_EQ(r.outcome, ScanMatchOutcome::kMatched) << ToString(r.outcome);
  EXPECT_TRUE(r.recovered);
  EXPECT_NEAR(WrapAngle(r.increment.mean.theta - truth.theta), 0.0, 0.3 * kDeg);
  EXPECT_NEAR(r.increment.mean.x, truth.x, 0.03);
  EXPECT_NEAR(r.increment.mean.y, truth.y, 0.03);
}

TEST(ScanMatcher, ReturnsThePriorWhenTheScansHaveNothingToMatch) {
  LaserScan empty;
  empty.angle_min = static_cast<float>(-90.0 * kDeg);
  empty.angle_increment = static_cast<float>(0.5 * kDeg);
  empty.max_range = 30.0f;
  empty.ranges.assign(361, kNoReturn);
  ScanMatcher matcher(Options());
  const UncertainPose prior = Prior(Pose2{0.2, 0.0, 0.1}, 0.05, 0.1);
  // No reference yet.
  EXPECT_EQ(matcher.Match(empty, prior).outcome, ScanMatchOutcome::kTooFewPoints);
  matcher.SetReference(empty);
  const ScanMatchResult r = matcher.Match(empty, prior);
  EXPECT_EQ(r.outcome, ScanMatchOutcome::kTooFewPoints);
  EXPECT_EQ(r.increment.mean.x, prior.mean.x);
  EXPECT_EQ(r.increment.cov, prior.cov);
  // A reference of walls, a current scan of one short wall only: too few pairs.
  FakeWallScanner laser(sim::CorridorWalls(), Laser(), 1);
  matcher.SetReference(laser.Scan(Pose2{5.0, 0.0, 0.0}));
  LaserScan sparse = empty;
  for (int i = 170; i < 190; ++i) sparse.ranges[i] = 50.0f;  // beyond max_range: unused
  for (int i = 0; i < 30; ++i) sparse.ranges[i] = 1.2f;
  EXPECT_EQ(matcher.Match(sparse, prior).outcome, ScanMatchOutcome::kTooFewPoints);
  // A circle 0.7 m around the sensor in a 2.4 m wide corridor: nothing within reach.
  LaserScan circle = empty;
  circle.ranges.assign(361, 0.7f);
  const ScanMatchResult s = matcher.Match(circle, prior);
  EXPECT_EQ(s.outcome, ScanMatchOutcome::kTooFewPairs) << ToString(s.outcome);
  EXPECT_EQ(s.increment.cov, prior.cov);
}

// The directions are those of each beam's bearing, computed as the points were before they were
// kept (the matcher's results do not change), and follow a change of layout.
TEST(BeamDirections, AreEachBeamsBearingAndFollowTheLayout) {
  LaserScan scan;
  scan.angle_min = -1.5f;
  scan.angle_increment = 0.01f;
  scan.ranges.assign(301, 2.0f);
  BeamDirections directions;
  for (int layout = 0; layout < 3; ++layout) {
    if (layout == 1) scan.angle_increment = 0.02f;
    if (layout == 2) scan.ranges.assign(101, 2.0f);
    const std::vector<Vec2>& d = directions.Of(scan);
    ASSERT_EQ(d.size(), scan.ranges.size());
    for (size_t i = 0; i < d.size(); ++i) {
      const double phi = scan.angle_min + static_cast<double>(i) * scan.angle_increment;
      EXPECT_EQ(d[i].x(), std::cos(phi)) << layout << " " << i;
      EXPECT_EQ(d[i].y(), std::sin(phi)) << layout << " " << i;
    }
  }
  std::vector<Vec2> points;
  scan.sensor_pose = Pose2{0.1, 0.0, 0.0};
  scan.ranges[5] = kNoReturn;
  ScanPointsInRobotFrame(scan, directions.Of(scan), 0.1, 20.0, &points);
  ASSERT_EQ(points.size(), 100u);
  EXPECT_NEAR(points[0].x(), 0.1 + 2.0 * std::cos(-1.5), 1e-6);
  EXPECT_NEAR(points[0].y(), 2.0 * std::sin(-1.5), 1e-6);
}

TEST(ScanMatcher, ValidateNamesTheBadOption) {
  EXPECT_EQ(ScanMatchOptions{}.Validate(), "");
  ScanMatchOptions o;
  o.information_scale = 0.0;
  EXPECT_NE(o.Validate().find("information_scale"), std::string::npos);
  o = ScanMatchOptions{};
  o.final_distance = 0.5;
  EXPECT_NE(o.Validate().find("final_distance"), std::string::npos);
  o = ScanMatchOptions{};
  o.heading_search = 0.3;
  o.heading_step = 0.0;
  EXPECT_NE(o.Validate().find("heading_step"), std::string::npos);
  // The recovery search steps by heading_step too, with or without heading_search.
  o = ScanMatchOptions{};
  o.heading_search = 0.0;
  o.recovery_heading_search = 0.5;
  for (double step : {0.0, -0.01, std::numeric_limits<double>::quiet_NaN()}) {
    o.heading_step = step;
    EXPECT_NE(o.Validate().find("heading_step"), std::string::npos) << step;
  }
}

}  // namespace
}  // namespace atlas
