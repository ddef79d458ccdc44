#include "core/sonar/sonar_map_bootstrapper.h"

#include <gtest/gtest.h>

#include <Eigen/Cholesky>
#include <cmath>
#include <memory>
#include <random>

#include "core/sonar/sonar_local_map.h"
#include "core/testing/degrees.h"
#include "core/testing/fake_sonar_ring.h"

namespace atlas {
namespace {

SonarLocalMapOptions RingOptions() {
  SonarLocalMapOptions o;
  o.sensors = RangeSensors::kSonar;
  o.ring = FakeSonarRing24();
  o.line_map.capacity = 10;
  return o;
}

// A frame's map made by driving along +x from the origin (the map-frame origin, as after
// Genesis) with exact odometry, then the readings of a juvenile driving on from there.
struct Frame {
  std::vector<sim::Wall> walls;
  SonarLocalMap map{RingOptions()};
  std::mt19937_64 rng{5};
  Pose2 truth{};
  Pose2 juvenile_start;  // truth when the juvenile is seeded
  std::vector<JuvenileScan> z;

  Frame(std::vector<sim::Wall> w, int map_steps, int juvenile_steps) : walls(std::move(w)) {
    const Pose2 u{0.05, 0.0, 0.0};
    for (int i = 0; i < map_steps; ++i) {
      map.UpdateWithSonar(Fire(), true);
      truth = Compose(truth, u);
      map.Predict(u);
    }
    juvenile_start = truth;
    // The juvenile turns slightly while it drives on.
    const Pose2 v{0.05, 0.0, 0.01};
    for (int i = 0; i < juvenile_steps; ++i) {
      truth = Compose(truth, v);
      JuvenileScan s;
      s.odometry_delta = v;
      s.sonar = Fire();
      z.push_back(s);
    }
  }
  SonarReading Fire() { return FireFakeSonarRing(walls, FakeSonarRing24(), truth, 0.01, rng); }

  // The seed x_i*: `offset` from the truth when the juvenile is seeded, covariance `seed_cov`.
  UncertainPose Seed(const Pose2& offset, const Mat3& seed_cov) const {
    return UncertainPose{Compose(juvenile_start, offset), seed_cov};
  }
  // The juvenile's trial map: a clone of the frame's map at that seed, run through Z without
  // new features (Section III-E).
  std::unique_ptr<LocalMap> Trial(const Pose2& offset, const Mat3& seed_cov) const {
    std::unique_ptr<LocalMap> trial = map.Clone();
    trial->ResetRobotPose(Seed(offset, seed_cov));
    for (const JuvenileScan& s : z) {
      trial->Predict(s.odometry_delta);
      trial->UpdateWithSonar(s.sonar, false);
    }
    return trial;
  }
};

// A corridor widening along x: two walls 39 degrees apart (y = +-(1.2 + 0.35 x)).
std::vector<sim::Wall> WideningCorridor() {
  return {{Vec2(-3, 0.15), Vec2(8, 4.0)}, {Vec2(-3, -0.15), Vec2(8, -4.0)}};
}

const Mat3 kLooseSeed = Vec3(0.3 * 0.3, 0.3 * 0.3, 0.2 * 0.2).asDiagonal();

double Nees(const UncertainPose& p, const Pose2& truth) {
  const Vec3 e(p.mean.x - truth.x, p.mean.y - truth.y, WrapAngle(p.mean.theta - truth.theta));
  return e.dot(p.cov.ldlt().solve(e));
}

int LinesAlong(const std::vector<MapLine>& lines, double alpha) {
  int n = 0;
  for (const MapLine& l : lines) n += std::abs(std::sin(l.alpha - alpha)) < 0.05 ? 1 : 0;
  return n;
}

TEST(SonarMapBootstrapper, SolvesTheTruePoseFromASeedFarOff) {
  const Frame f(WideningCorridor(), 50, 12);
  const std::vector<MapLine> lines = f.map.Lines();
  ASSERT_GE(LinesAlong(lines, std::atan(0.35) + 90 * kDeg), 1) << "one wall is mapped";
  ASSERT_GE(LinesAlong(lines, -std::atan(0.35) + 90 * kDeg), 1) << "the other wall is mapped";
  // Seeded 0.5 m and 10 degrees off.
  const Pose2 offset{0.35, -0.35, 10 * kDeg};
  const std::unique_ptr<LocalMap> trial = f.Trial(offset, kLooseSeed);
  const PoseBootstrap r =
      SonarMapBootstrapper().Solve(*trial, f.map, f.z, f.Seed(offset, kLooseSeed));
  ASSERT_EQ(r.outcome, BootstrapOutcome::kSolved);
  EXPECT_NEAR(r.pose.mean.x, f.truth.x, 0.05);
  EXPECT_NEAR(r.pose.mean.y, f.truth.y, 0.05);
  EXPECT_NEAR(WrapAngle(r.pose.mean.theta - f.truth.theta), 0.0, 2 * kDeg);
  EXPECT_LT(Nees(r.pose, f.truth), 16.27);  // 3 dof, 99.9 %
  // M_i^new: the frame's features untouched (nothing of the seed in them), the robot at w's
  // solution and correlated with them.
  ASSERT_NE(r.map, nullptr);
  const std::vector<MapLine> fresh = r.map->Lines();
  ASSERT_EQ(fresh.size(), lines.size());
  for (size_t k = 0; k < lines.size(); ++k) {
    EXPECT_EQ(fresh[k].rho, lines[k].rho);
    EXPECT_EQ(fresh[k].alpha, lines[k].alpha);
    EXPECT_EQ(fresh[k].cov, lines[k].cov);
  }
  EXPECT_NEAR(r.map->RobotPose().mean.x, r.pose.mean.x, 1e-12);
  const auto* sonar = dynamic_cast<const SonarLocalMap*>(r.map.get());
  ASSERT_NE(sonar, nullptr);
  EXPECT_GT(sonar->Ekf().Covariance().topRightCorner(3, 2 * lines.size()).norm(), 0.0);
  EXPECT_EQ(sonar->Initializer().Vantages().size(), 0u);
}

TEST(SonarMapBootstrapper, SolutionDoesNotDependOnTheSeed) {
  const Frame f(WideningCorridor(), 50, 12);
  const std::unique_ptr<LocalMap> ta = f.Trial(Pose2{0.35, -0.35, 10 * kDeg}, kLooseSeed);
  const std::unique_ptr<LocalMap> tb = f.Trial(Pose2{-0.3, 0.3, -8 * kDeg}, kLooseSeed);
  const SonarMapBootstrapper w;
  const SonarBootstrapResult a = w.SolvePose(f.map, ta->RobotPose(), f.z);
  const SonarBootstrapResult b = w.SolvePose(f.map, tb->RobotPose(), f.z);
  ASSERT_EQ(a.outcome, BootstrapOutcome::kSolved);
  ASSERT_EQ(b.outcome, BootstrapOutcome::kSolved);
  EXPECT_NEAR(a.pose.mean.x, b.pose.mean.x, 1e-4);
  EXPECT_NEAR(a.pose.mean.y, b.pose.mean.y, 1e-4);
  EXPECT_NEAR(WrapAngle(a.pose.mean.theta - b.pose.mean.theta), 0.0, 1e-5);
  EXPECT_LT((a.pose.cov - b.pose.cov).norm(), 1e-3 * a.pose.cov.norm());
  EXPECT_EQ(a.paired, b.paired);
  // The seeded trial maps themselves still differ.
  EXPECT_GT(std::abs(WrapAngle(ta->RobotPose().mean.theta - tb->RobotPose().mean.theta)), 5e-3);
}

// The start estimate is the seed moved by Z's odometry, not the juvenile's pose: a juvenile
// whose clone was drawn 0.6 m off during probation (confident, sigma 3 cm) still gets the true
// solution from a good seed; started at the juvenile's pose, w pairs its readings from there and
// does not find it.
TEST(SonarMapBootstrapper, StartsFromTheSeedMovedByOdometryNotFromTheJuvenilesPose) {
  const Frame f(WideningCorridor(), 50, 12);
  const std::unique_ptr<LocalMap> trial = f.Trial(Pose2{}, kLooseSeed);
  const Mat3 confident = Vec3(0.03 * 0.03, 0.03 * 0.03, 0.01 * 0.01).asDiagonal();
  trial->ResetRobotPose(UncertainPose{Compose(f.truth, Pose2{0.6, 0.0, 0.0}), confident});
  const UncertainPose seed = f.Seed(Pose2{0.1, -0.1, 2 * kDeg}, kLooseSeed);

  // The start: the seed composed with every increment of Z, its covariance grown.
  const UncertainPose start = SonarMapBootstrapper::DeadReckonedSeed(f.map, seed, f.z);
  Pose2 moved = seed.mean;
  for (const JuvenileScan& s : f.z) moved = Compose(moved, s.odometry_delta);
  EXPECT_NEAR(start.mean.x, moved.x, 1e-12);
  EXPECT_NEAR(start.mean.y, moved.y, 1e-12);
  EXPECT_NEAR(start.mean.theta, moved.theta, 1e-12);
  EXPECT_GT(start.cov(0, 0), kLooseSeed(0, 0));
  EXPECT_GT(start.cov(2, 2), kLooseSeed(2, 2));

  const PoseBootstrap r = SonarMapBootstrapper().Solve(*trial, f.map, f.z, seed);
  ASSERT_EQ(r.outcome, BootstrapOutcome::kSolved);
  EXPECT_NEAR(r.pose.mean.x, f.truth.x, 0.05);
  EXPECT_NEAR(r.pose.mean.y, f.truth.y, 0.05);
  EXPECT_LT(Nees(r.pose, f.truth), 16.27);

  SonarBootstrapOptions o;
  o.dead_reckoned_start = false;
  const PoseBootstrap from_juvenile = SonarMapBootstrapper(o).Solve(*trial, f.map, f.z, seed);
  EXPECT_FALSE(from_juvenile.outcome == BootstrapOutcome::kSolved &&
               std::abs(from_juvenile.pose.mean.x - f.truth.x) < 0.05)
      << "started 0.6 m off with sigma 3 cm, w should not find the truth";
}

TEST(SonarMapBootstrapper, ParallelWallsOrOneWallLeaveThePoseUndetermined) {
  // Side walls far beyond the ends: nothing fixes the position along them.
  const Frame corridor({{Vec2(-30, 1.2), Vec2(40, 1.2)}, {Vec2(-30, -1.2), Vec2(40, -1.2)}}, 50,
                       12);
  ASSERT_GE(LinesAlong(corridor.map.Lines(), 90 * kDeg), 2);
  const Mat3 tight = Vec3(0.05 * 0.05, 0.05 * 0.05, 0.02 * 0.02).asDiagonal();
  const Pose2 off{0.1, 0.05, 0.02};
  const std::unique_ptr<LocalMap> trial = corridor.Trial(off, tight);
  const SonarMapBootstrapper w;
  const PoseBootstrap r = w.Solve(*trial, corridor.map, corridor.z, corridor.Seed(off, tight));
  EXPECT_EQ(r.outcome, BootstrapOutcome::kUndetermined);
  EXPECT_EQ(r.map, nullptr);

  const Frame one({{Vec2(-30, 1.2), Vec2(40, 1.2)}}, 50, 12);
  ASSERT_GE(LinesAlong(one.map.Lines(), 90 * kDeg), 1);
  const std::unique_ptr<LocalMap> trial1 = one.Trial(off, tight);
  EXPECT_EQ(w.Solve(*trial1, one.map, one.z, one.Seed(off, tight)).outcome,
            BootstrapOutcome::kUndetermined);
}

TEST(SonarMapBootstrapper, ReadingsTheMapDoesNotExplainAreUndetermined) {
  const Frame f(WideningCorridor(), 50, 12);
  std::vector<JuvenileScan> blind = f.z;
  for (JuvenileScan& s : blind)
    for (SonarReturn& ret : s.sonar.returns) ret.range = kNoReturn;
  const std::unique_ptr<LocalMap> trial = f.Trial(Pose2{}, kLooseSeed);
  const UncertainPose seed = f.Seed(Pose2{}, kLooseSeed);
  EXPECT_EQ(SonarMapBootstrapper().Solve(*trial, f.map, blind, seed).outcome,
            BootstrapOutcome::kUndetermined);
  EXPECT_EQ(SonarMapBootstrapper().Solve(*trial, f.map, {}, seed).outcome,
            BootstrapOutcome::kFailed);
}

TEST(SonarBootstrapOptions, Validate) {
  EXPECT_EQ(SonarBootstrapOptions().Validate(), "");
  SonarBootstrapOptions o;
  o.min_returns = 2;
  EXPECT_NE(o.Validate(), "");
  o = SonarBootstrapOptions();
  o.residual_gate = 1.0;
  EXPECT_NE(o.Validate(), "");
  o = SonarBootstrapOptions();
  o.rounds = 0;
  EXPECT_NE(o.Validate(), "");
}

}  // namespace
}  // namespace atlas
