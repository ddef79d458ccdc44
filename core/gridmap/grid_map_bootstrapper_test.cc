#include "core/gridmap/grid_map_bootstrapper.h"

#include <gtest/gtest.h>

#include <cmath>

#include "core/testing/fake_wall_scanner.h"
#include "core/testing/grid_scenes.h"

namespace atlas {
namespace {

// A frame's grid made along a straight drive through `walls` (world = frame).
GridLocalMap FrameAlong(const std::vector<sim::Wall>& walls, const Pose2& start, double step,
                        int steps) {
  GridLocalMapOptions o;
  o.odometry = FakeWallMapOptions().odometry;
  o.max_extent = 100.0;
  GridLocalMap map(o);
  FakeWallScanner scanner(walls, FrontLaser(), 11);
  map.ResetRobotPose(UncertainPose{start, Mat3::Zero()});
  Pose2 truth = start;
  map.Update(scanner.Scan(truth), true);
  for (int k = 0; k < steps; ++k) {
    truth = Compose(truth, Pose2{step, 0.0, 0.0});
    map.Predict(Pose2{step, 0.0, 0.0});
    map.Update(scanner.Scan(truth), true);
  }
  return map;
}

// Four scans along a path ending at `end`, and a juvenile's map seeded at `seed_mean`.
struct Juvenile {
  std::vector<JuvenileScan> z;
  GridLocalMap map;
  UncertainPose seed;
};
Juvenile JuvenileAt(const std::vector<sim::Wall>& walls, const GridLocalMap& frame,
                    const Pose2& end, const Pose2& seed_mean, double seed_sigma) {
  FakeWallScanner scanner(walls, FrontLaser(), 12);
  Juvenile j{{}, frame, {}};
  const Pose2 u{0.15, 0.0, 0.05};
  Pose2 truth = Compose(end, Inverse(Compose(u, Compose(u, u))));
  for (int k = 0; k < 4; ++k) {
    if (k > 0) truth = Compose(truth, u);
    j.z.push_back(JuvenileScan{k > 0 ? u : Pose2{}, ScanObservation(scanner.Scan(truth)), {}, {}});
  }
  j.seed = UncertainPose{seed_mean, Mat3::Identity() * seed_sigma * seed_sigma};
  j.seed.cov(2, 2) = 0.01;
  j.map.ResetRobotPose(j.seed);
  return j;
}

TEST(GridMapBootstrapper, SolvesAPoseHalfAMetreFromTheSeed) {
  const std::vector<sim::Wall> walls = RoomWalls();
  const GridLocalMap frame = FrameAlong(walls, Pose2{-3.5, 0.0, 0.0}, 0.2, 30);
  const Pose2 truth{1.0, -1.0, 0.7};
  const Juvenile j = JuvenileAt(walls, frame, truth, Pose2{1.4, -0.7, 0.75}, 0.3);
  const PoseBootstrap r = GridMapBootstrapper(frame.Options()).Solve(j.map, frame, j.z, j.seed);
  ASSERT_EQ(r.outcome, BootstrapOutcome::kSolved);
  EXPECT_NEAR(r.pose.mean.x, truth.x, 0.05);
  EXPECT_NEAR(r.pose.mean.y, truth.y, 0.05);
  EXPECT_NEAR(WrapAngle(r.pose.mean.theta - truth.theta), 0.0, 0.02);
  EXPECT_LT(std::sqrt(r.pose.cov(0, 0)), 0.1);
  EXPECT_EQ(r.map, nullptr);
}

// w in slices of a small work bound ends with the pose of the whole search.
TEST(GridMapBootstrapper, SlicedSearchEqualsTheWholeSolve) {
  const std::vector<sim::Wall> walls = RoomWalls();
  const GridLocalMap frame = FrameAlong(walls, Pose2{-3.5, 0.0, 0.0}, 0.2, 30);
  const Juvenile j = JuvenileAt(walls, frame, Pose2{1.0, -1.0, 0.7}, Pose2{1.4, -0.7, 0.75}, 0.3);
  const PoseBootstrap whole = GridMapBootstrapper(frame.Options()).Solve(j.map, frame, j.z, j.seed);
  ASSERT_EQ(whole.outcome, BootstrapOutcome::kSolved);
  GridLocalMapOptions small = frame.Options();
  small.bootstrap.work_per_step = 20000;
  const GridMapBootstrapper w(small);
  const std::unique_ptr<BootstrapSearch> search = w.Begin(j.map, frame, j.z, j.seed);
  int slices = 1;
  while (!search->Continue(j.map, frame, j.z)) ++slices;
  EXPECT_GT(slices, 10);
  const PoseBootstrap r = search->TakeResult();
  ASSERT_EQ(r.outcome, BootstrapOutcome::kSolved);
  EXPECT_DOUBLE_EQ(r.pose.mean.x, whole.pose.mean.x);
  EXPECT_DOUBLE_EQ(r.pose.mean.y, whole.pose.mean.y);
  EXPECT_DOUBLE_EQ(r.pose.mean.theta, whole.pose.mean.theta);
}

TEST(GridMapBootstrapper, ACorridorsLengthIsUndeterminedAndAnotherPlaceFails) {
  const std::vector<sim::Wall> corridor = LongCorridorWalls();
  const GridLocalMap frame = FrameAlong(corridor, Pose2{0.0, 0.0, 0.0}, 0.2, 30);
  const Juvenile along =
      JuvenileAt(corridor, frame, Pose2{3.0, 0.0, 0.1}, Pose2{3.4, 0.1, 0.1}, 0.3);
  EXPECT_EQ(
      GridMapBootstrapper(frame.Options()).Solve(along.map, frame, along.z, along.seed).outcome,
      BootstrapOutcome::kUndetermined);
  // Scans of the room searched for in the corridor's grid.
  const Juvenile room =
      JuvenileAt(RoomWalls(), frame, Pose2{1.0, -1.0, 0.7}, Pose2{1.0, -1.0, 0.7}, 0.3);
  EXPECT_EQ(GridMapBootstrapper(frame.Options()).Solve(room.map, frame, room.z, room.seed).outcome,
            BootstrapOutcome::kFailed);
}

}  // namespace
}  // namespace atlas
