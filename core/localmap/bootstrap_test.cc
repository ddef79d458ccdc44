#include "core/localmap/bootstrap.h"

#include <gtest/gtest.h>

#include <Eigen/LU>

#include "core/localmap/line_ekf_map.h"
#include "core/localmap/line_extraction.h"
#include "core/localmap/line_model.h"
#include "core/testing/fake_wall_scanner.h"

namespace atlas {
namespace {

std::vector<MapLine> MapOf(const std::vector<sim::Wall>& walls, double sigma_rho = 0.005,
                           double sigma_alpha = 0.002) {
  std::vector<MapLine> map;
  for (int i = 0; i < static_cast<int>(walls.size()); ++i) {
    const Vec2 l = LineThroughPoints(walls[i].a, walls[i].b);
    MapLine m;
    m.id = 10 + i;
    m.rho = l(0);
    m.alpha = l(1);
    m.cov = Vec2(sigma_rho * sigma_rho, sigma_alpha * sigma_alpha).asDiagonal();
    m.endpoint_a = walls[i].a;
    m.endpoint_b = walls[i].b;
    map.push_back(m);
  }
  return map;
}

// Two scans: one at `earlier`, one at `current`, both seen from the true poses.
std::vector<BootstrapScan> Scans(const std::vector<sim::Wall>& walls, const Pose2& earlier,
                                 const Pose2& current, uint64_t seed) {
  FakeLaserOptions lo;
  lo.range_sigma = 0.01;
  FakeWallScanner scanner(walls, lo, seed);
  const LineExtractionOptions eo;
  BootstrapScan s0, s1;
  s0.pose_in_current = Between(current, earlier);
  s0.pose_cov = Mat3(Vec3(1e-6, 1e-6, 1e-7).asDiagonal());
  s0.lines = ExtractRobotFrameLines(scanner.Scan(earlier), eo);
  s1.lines = ExtractRobotFrameLines(scanner.Scan(current), eo);
  return {s0, s1};
}

const std::vector<sim::Wall> kRoom = {{Vec2(4.0, -1.5), Vec2(4.0, 2.0)},
                                      {Vec2(-2.0, 2.0), Vec2(4.0, 2.0)},
                                      {Vec2(-2.0, -1.5), Vec2(4.0, -1.5)}};

TEST(BootstrapTest, SolvesThePoseFromFeaturesIndependentlyOfTheSeed) {
  const Pose2 truth{1.0, 0.5, 0.2};
  const auto scans = Scans(kRoom, Pose2{0.7, 0.45, 0.15}, truth, 21);
  const std::vector<MapLine> map = MapOf(kRoom);
  UncertainPose seed_a{Pose2{1.3, 0.3, 0.25}, Mat3(Vec3(0.2, 0.2, 0.01).asDiagonal())};
  UncertainPose seed_b{Pose2{0.8, 0.6, 0.17}, Mat3(Vec3(0.1, 0.1, 0.01).asDiagonal())};
  const BootstrapResult a = Bootstrap(map, scans, seed_a, BootstrapOptions(), AssociationOptions());
  const BootstrapResult b = Bootstrap(map, scans, seed_b, BootstrapOptions(), AssociationOptions());
  ASSERT_EQ(a.status, BootstrapStatus::kSolved);
  ASSERT_EQ(b.status, BootstrapStatus::kSolved);
  EXPECT_GE(a.matches.size(), 5u);
  EXPECT_NEAR(a.pose.mean.x, truth.x, 0.03);
  EXPECT_NEAR(a.pose.mean.y, truth.y, 0.03);
  EXPECT_NEAR(a.pose.mean.theta, truth.theta, 0.01);
  // Same matches, same pose: the seed did not leak into the solution.
  ASSERT_EQ(a.matches.size(), b.matches.size());
  EXPECT_NEAR(a.pose.mean.x, b.pose.mean.x, 1e-9);
  EXPECT_NEAR(a.pose.mean.y, b.pose.mean.y, 1e-9);
  EXPECT_NEAR(a.pose.mean.theta, b.pose.mean.theta, 1e-9);
  // The covariance explains the error.
  const Vec3 e(truth.x - a.pose.mean.x, truth.y - a.pose.mean.y,
               WrapAngle(truth.theta - a.pose.mean.theta));
  EXPECT_LT(e.dot(a.pose.cov.inverse() * e), 16.27);  // chi2(3) at 0.999
  EXPECT_EQ(a.d_lines.cols(), 2 * static_cast<int>(a.feature_index.size()));
}

TEST(BootstrapTest, ParallelWallsOnlyAreUnderconstrained) {
  const std::vector<sim::Wall> corridor = {kRoom[1], kRoom[2]};
  const Pose2 truth{1.0, 0.5, 0.2};
  const auto scans = Scans(corridor, Pose2{0.7, 0.45, 0.15}, truth, 22);
  UncertainPose seed{Pose2{1.3, 0.3, 0.25}, Mat3(Vec3(0.2, 0.2, 0.01).asDiagonal())};
  const BootstrapResult r =
      Bootstrap(MapOf(corridor), scans, seed, BootstrapOptions(), AssociationOptions());
  EXPECT_EQ(r.status, BootstrapStatus::kUnderconstrained);
  EXPECT_GE(r.matches.size(), 2u);
}

TEST(BootstrapTest, NothingMatchedIsTooFew) {
  const Pose2 truth{1.0, 0.5, 0.2};
  const auto scans = Scans(kRoom, Pose2{0.7, 0.45, 0.15}, truth, 23);
  UncertainPose seed{truth, Mat3(Vec3(0.01, 0.01, 0.001).asDiagonal())};
  EXPECT_EQ(Bootstrap({}, scans, seed, BootstrapOptions(), AssociationOptions()).status,
            BootstrapStatus::kTooFewMatches);
  // Seeded far away (other side of the building): nothing gates in.
  seed.mean = Pose2{30.0, -20.0, 2.0};
  EXPECT_EQ(Bootstrap(MapOf(kRoom), scans, seed, BootstrapOptions(), AssociationOptions()).status,
            BootstrapStatus::kTooFewMatches);
}

TEST(BootstrapTest, EkfTakesTheSolutionWithCrossCovariances) {
  LocalMapOptions o;
  LineEkfMap map(o);
  FakeLaserOptions lo;
  FakeWallScanner scanner(kRoom, lo, 30);
  map.Update(scanner.Scan(Pose2{}), true);
  ASSERT_EQ(map.Complexity(), 3);
  const Pose2 truth{0.4, 0.1, 0.05};
  const auto scans = Scans(kRoom, Pose2{0.3, 0.1, 0.04}, truth, 31);
  UncertainPose seed{Pose2{0.5, 0.0, 0.0}, Mat3(Vec3(0.1, 0.1, 0.01).asDiagonal())};
  const BootstrapResult r = Bootstrap(map.Lines(), scans, seed, o.bootstrap, o.association);
  ASSERT_EQ(r.status, BootstrapStatus::kSolved);
  map.SetRobotPoseFromFeatures(r.pose.mean, r.observation_cov, r.feature_index, r.d_lines);
  const Eigen::MatrixXd& p = map.Covariance();
  EXPECT_TRUE(p.isApprox(p.transpose()));
  EXPECT_GT(p.determinant(), 0.0);
  EXPECT_FALSE(p.topRightCorner(3, p.cols() - 3).isZero());
  EXPECT_NEAR(map.RobotPose().mean.x, truth.x, 0.03);
}

}  // namespace
}  // namespace atlas
