#include "core/sonar/sonar_local_map.h"

#include <gtest/gtest.h>

#include <Eigen/Cholesky>
#include <Eigen/LU>
#include <cmath>
#include <numbers>
#include <random>

#include "core/sonar/sonar_geometry.h"
#include "core/testing/fake_sonar_ring.h"
#include "core/testing/fake_wall_scanner.h"

namespace atlas {
namespace {

std::vector<sim::Wall> Corridor() {
  return {{Vec2(-2, 1.2), Vec2(14, 1.2)},
          {Vec2(-2, -1.2), Vec2(14, -1.2)},
          {Vec2(14, -1.2), Vec2(14, 1.2)}};
}

SonarLocalMapOptions Options() {
  SonarLocalMapOptions o;
  o.sensors = RangeSensors::kSonar;
  o.line_map = FakeWallMapOptions();
  o.line_map.capacity = 10;
  return o;
}

// Drives straight along the corridor with exact odometry (the filter still adds its noise).
SonarLocalMap DriveCorridor(int steps, std::vector<SonarUpdate>* updates = nullptr) {
  SonarLocalMap map(Options());
  const std::vector<SonarTransducer> ring = FakeSonarRing24();
  std::mt19937_64 rng(7);
  Pose2 truth{};
  for (int i = 0; i < steps; ++i) {
    const SonarUpdate up =
        map.UpdateSonar(FireFakeSonarRing(Corridor(), ring, truth, 0.01, rng), ring, true);
    if (updates) updates->push_back(up);
    const Pose2 u{0.05, 0.0, 0.0};
    truth = Compose(truth, u);
    map.Predict(u);
  }
  return map;
}

TEST(SonarLocalMap, InitialisesCorridorWallsAndTracksThePose) {
  std::vector<SonarUpdate> ups;
  const SonarLocalMap map = DriveCorridor(120, &ups);  // 6 m
  int matched = 0;
  for (const SonarUpdate& u : ups) matched += u.matched;
  EXPECT_GT(matched, 100);
  const std::vector<MapLine> lines = map.Lines();
  ASSERT_GE(lines.size(), 2u);
  int walls_found = 0;
  for (const MapLine& l : lines) {
    // Each line is one of the corridor walls y = +-1.2 or the end wall x = 14.
    const bool side =
        std::abs(std::abs(l.alpha) - std::numbers::pi / 2) < 0.03 && std::abs(l.rho - 1.2) < 0.05;
    const bool end = std::abs(l.alpha) < 0.03 && std::abs(l.rho - 14.0) < 0.1;
    EXPECT_TRUE(side || end) << l.rho << " " << l.alpha;
    walls_found += side ? 1 : 0;
  }
  EXPECT_EQ(walls_found, 2);
  const UncertainPose p = map.RobotPose();
  const Vec3 e(p.mean.x - 6.0, p.mean.y, p.mean.theta);
  EXPECT_LT(e.dot(p.cov.ldlt().solve(e)), 16.3);  // 3 dof, 99.9 %
  // Sonar updates bound the lateral and heading uncertainty below dead reckoning's.
  SonarLocalMap odometry_only(Options());
  for (int i = 0; i < 120; ++i) odometry_only.Predict(Pose2{0.05, 0.0, 0.0});
  EXPECT_LT(p.cov(1, 1), 0.7 * odometry_only.RobotPose().cov(1, 1));
  EXPECT_LT(p.cov(2, 2), 0.7 * odometry_only.RobotPose().cov(2, 2));
}

TEST(SonarLocalMap, UpdateReducesUncertaintyAndGatesOutliers) {
  SonarLocalMap map = DriveCorridor(60);
  ASSERT_GE(map.Complexity(), 2);
  // Let the pose uncertainty grow, then fire one transducer at the left wall.
  for (int i = 0; i < 20; ++i) map.Predict(Pose2{0.0, 0.0, 0.0});
  map.ResetRobotPose(UncertainPose{map.RobotPose().mean, Vec3(0.01, 0.01, 0.001).asDiagonal()});
  const std::vector<SonarTransducer> ring = FakeSonarRing24();
  // Transducer 5 faces 82.5 deg: the left wall y = 1.2 is in its cone.
  const double expected =
      PredictSonarRange(map.RobotPose().mean, ring[5], 1.2, std::numbers::pi / 2).range;
  SonarReading good;
  good.returns.push_back(SonarReturn{5, static_cast<float>(expected)});
  SonarLocalMap copy = *static_cast<SonarLocalMap*>(map.Clone().get());
  const double var_before = map.RobotPose().cov(1, 1);
  SonarUpdate up = map.UpdateSonar(good, ring, false);
  EXPECT_EQ(up.matched, 1);
  EXPECT_LT(map.RobotPose().cov(1, 1), 0.5 * var_before);
  // A multipath return 1.5 m too long (behind the mapped wall that echoes in the cone) is
  // neither used nor kept for initialisation.
  SonarReading bad;
  bad.returns.push_back(SonarReturn{5, static_cast<float>(expected + 1.5)});
  up = copy.UpdateSonar(bad, ring, false);
  EXPECT_EQ(up.matched, 0);
  EXPECT_EQ(up.buffered, 0);
  EXPECT_EQ(up.behind, 1);
  EXPECT_DOUBLE_EQ(copy.RobotPose().cov(1, 1), var_before);
  // Out-of-ring transducers and no-returns are skipped.
  SonarReading junk;
  junk.returns = {SonarReturn{99, 1.0f}, SonarReturn{-1, 1.0f}, SonarReturn{3, kNoReturn}};
  up = copy.UpdateSonar(junk, ring, true);
  EXPECT_EQ(up.usable, 0);
}

TEST(SonarLocalMap, JuvenileDoesNotAddFeatures) {
  SonarLocalMap map(Options());
  const std::vector<SonarTransducer> ring = FakeSonarRing24();
  std::mt19937_64 rng(1);
  Pose2 truth{};
  for (int i = 0; i < 80; ++i) {
    map.UpdateSonar(FireFakeSonarRing(Corridor(), ring, truth, 0.01, rng), ring, false);
    truth = Compose(truth, Pose2{0.05, 0, 0});
    map.Predict(Pose2{0.05, 0, 0});
  }
  EXPECT_EQ(map.Complexity(), 0);
  EXPECT_GT(map.Initializer().Returns().size(), 10u);
}

TEST(SonarLocalMap, SensorModesAndSerialisation) {
  SonarLocalMapOptions o = Options();
  o.sensors = RangeSensors::kLaser;
  SonarLocalMap laser_only(o);
  const std::vector<SonarTransducer> ring = FakeSonarRing24();
  std::mt19937_64 rng(2);
  const SonarUpdate up =
      laser_only.UpdateSonar(FireFakeSonarRing(Corridor(), ring, Pose2{}, 0.0, rng), ring, true);
  EXPECT_EQ(up.usable, 0);
  SonarLocalMap sonar_only(Options());
  LaserScan scan;
  scan.angle_increment = 0.01f;
  scan.max_range = 30.0f;
  scan.ranges.assign(100, 2.0f);
  EXPECT_EQ(sonar_only.Update(scan, true).observations, 0);
  EXPECT_EQ(sonar_only.Complexity(), 0);

  const SonarLocalMap map = DriveCorridor(80);
  SonarLocalMap back(Options());
  ASSERT_TRUE(back.Deserialize(map.Serialize()));
  EXPECT_EQ(back.Complexity(), map.Complexity());
  EXPECT_TRUE(back.Ekf().Covariance().isApprox(map.Ekf().Covariance()));
  std::string bad = map.Serialize();
  bad[0] ^= 1;
  EXPECT_FALSE(back.Deserialize(bad));
  EXPECT_FALSE(back.Deserialize(bad.substr(0, 5)));
}

// The sonar map's image is its EKF's: one with more features than this map's capacity is
// refused.
TEST(SonarLocalMap, DeserializeRefusesMoreFeaturesThanCapacity) {
  const SonarLocalMap map = DriveCorridor(80);
  const int n = map.Complexity();
  ASSERT_GE(n, 2);
  SonarLocalMapOptions o = Options();
  o.line_map.capacity = n;
  SonarLocalMap exact(o);
  ASSERT_TRUE(exact.Deserialize(map.Serialize()));
  EXPECT_EQ(exact.Serialize(), map.Serialize());
  o.line_map.capacity = n - 1;
  SonarLocalMap smaller(o);
  EXPECT_FALSE(smaller.Deserialize(map.Serialize()));
  EXPECT_EQ(smaller.Complexity(), 0);
}

TEST(SonarLocalMapOptions, Validate) {
  SonarLocalMapOptions o;
  EXPECT_EQ(o.Validate(), "");
  o.init.min_support = 1;
  EXPECT_NE(o.Validate().find("init.min_support"), std::string::npos);
  o = SonarLocalMapOptions();
  o.update.loose_gate = 0.5;
  EXPECT_NE(o.Validate().find("update.gate"), std::string::npos);
  o = SonarLocalMapOptions();
  o.model.cone_scale = 10;
  EXPECT_NE(o.Validate(), "");
}

}  // namespace
}  // namespace atlas
