#include "core/gridmap/grid_local_map.h"

#include <gtest/gtest.h>

#include <Eigen/LU>
#include <algorithm>
#include <cmath>
#include <cstring>
#include <string>

#include "core/atlas/byte_image.h"
#include "core/testing/fake_wall_scanner.h"
#include "core/testing/grid_scenes.h"

namespace atlas {
namespace {

// An odometry noise model that covers the biased odometry of the drives below (a few per cent
// of the distance and 0.05 rad per metre).
GridLocalMapOptions GenerousOdometry() {
  GridLocalMapOptions o;
  o.odometry.xy_var_per_m = 0.003;
  o.odometry.theta_var_per_m = 0.003;
  o.odometry.theta_var_per_rad = 0.01;
  return o;
}

// Drives `map` along `truth` (world = frame, starting at truth[0]) with odometry whose
// translation is scaled by `scale` and whose heading drifts by `turn_bias` per step.
Pose2 Drive(GridLocalMap* map, const std::vector<sim::Wall>& walls, const std::vector<Pose2>& truth,
            double scale, double turn_bias, Pose2* dead_reckoned) {
  FakeWallScanner scanner(walls, FrontLaser(), 7);
  map->ResetRobotPose(UncertainPose{truth[0], Mat3::Zero()});
  *dead_reckoned = truth[0];
  map->Update(scanner.Scan(truth[0]), true);
  for (size_t k = 1; k < truth.size(); ++k) {
    Pose2 u = Between(truth[k - 1], truth[k]);
    u = Pose2{u.x * scale, u.y * scale, u.theta + turn_bias};
    *dead_reckoned = Compose(*dead_reckoned, u);
    map->Predict(u);
    map->Update(scanner.Scan(truth[k]), true);
  }
  return map->RobotPose().mean;
}

TEST(GridLocalMap, AlignsEveryScanAndBeatsBiasedOdometryInARoom) {
  const std::vector<sim::Wall> walls = RoomWalls();
  std::vector<Pose2> truth;
  for (int k = 0; k <= 60; ++k) truth.push_back(Pose2{-3.5 + 0.1 * k, 0.02 * k, 0.01 * k});
  GridLocalMap map(GenerousOdometry());
  Pose2 odometry;
  const Pose2 end = Drive(&map, walls, truth, 1.08, 0.004, &odometry);
  const Pose2& t = truth.back();
  // Dead reckoning ends 0.5 m and 14 degrees off; the grid keeps the robot within 5 cm.
  EXPECT_GT(std::hypot(odometry.x - t.x, odometry.y - t.y), 0.4);
  EXPECT_NEAR(end.x, t.x, 0.05);
  EXPECT_NEAR(end.y, t.y, 0.05);
  EXPECT_NEAR(WrapAngle(end.theta - t.theta), 0.0, 0.01);
  EXPECT_TRUE(map.LastUpdateMatched());
  const ScanUpdate u = map.Update(FakeWallScanner(walls, FrontLaser(), 9).Scan(t), false);
  EXPECT_GT(u.observations, 100);
  EXPECT_GT(u.matched, 0.9 * u.observations);
  // The covariance comes from the match: centimetres, not the odometry's decimetres.
  const Mat3 cov = map.RobotPose().cov;
  EXPECT_LT(std::sqrt(cov(0, 0)), 0.05);
  EXPECT_GT(cov.determinant(), 0.0);
}

// Driving 4 m along a featureless corridor with odometry 10 % long and turning 0.003 rad per
// step.
struct CorridorDrive {
  Pose2 end, odometry;
  Mat3 cov;
};
CorridorDrive DriveTheCorridor() {
  std::vector<Pose2> truth;
  for (int k = 0; k <= 40; ++k) truth.push_back(Pose2{0.1 * k, 0.0, 0.0});
  GridLocalMapOptions o = GenerousOdometry();
  o.max_extent = 100.0;
  GridLocalMap map(o);
  CorridorDrive d;
  d.end = Drive(&map, LongCorridorWalls(), truth, 1.1, 0.003, &d.odometry);
  d.cov = map.RobotPose().cov;
  return d;
}

TEST(GridLocalMap, TheCorridorsWallsFixTheCrossAxisAndTheHeading) {
  const CorridorDrive d = DriveTheCorridor();
  EXPECT_GT(std::abs(d.odometry.y), 0.1);
  EXPECT_NEAR(d.end.y, 0.0, 0.03);
  EXPECT_NEAR(d.end.theta, 0.0, 0.01);
}

// Along the corridor the pose follows the odometry (4.4 m for 4 m) with a growing variance:
// the aligner reports the length unconstrained (from the scan's surfaces, scan_alignment.h),
// so the grid's texture where scans were inserted does not hold the scan back.
TEST(GridLocalMap, TheCorridorsLengthTakesTheOdometryWithItsNoise) {
  const CorridorDrive d = DriveTheCorridor();
  EXPECT_NEAR(d.end.x, d.odometry.x, 0.1);
  EXPECT_GT(d.cov(0, 0), 25.0 * d.cov(1, 1));
}

TEST(GridLocalMap, IsBoundedByScanCountAndExtent) {
  const std::vector<sim::Wall> walls = LongCorridorWalls();
  FakeWallScanner scanner(walls, FrontLaser(), 3);
  GridLocalMapOptions o;
  o.insert_min_distance = 0.15;  // every second scan
  o.max_scans = 5;
  o.max_extent = 100.0;
  GridLocalMap by_count(o);
  o.max_scans = 1000;
  o.max_extent = 1.0;
  GridLocalMap by_extent(o);
  for (int k = 0; k <= 30; ++k) {
    for (GridLocalMap* m : {&by_count, &by_extent}) {
      if (k > 0) m->Predict(Pose2{0.1, 0.0, 0.0});
      m->Update(scanner.Scan(Pose2{0.1 * k, 0.0, 0.0}), true);
    }
    if (k == 4) {
      EXPECT_EQ(by_count.Complexity(), 3);  // at 0, 0.2 and 0.4 m
      EXPECT_LT(by_extent.Complexity(), by_extent.Capacity());
    }
  }
  EXPECT_EQ(by_count.Complexity(), by_count.Capacity());
  EXPECT_EQ(by_extent.Complexity(), by_extent.Capacity());
  // Scans inserted up to 1 m from the origin: within 1.5 m of 2.2 m, not of 3.5 m.
  EXPECT_TRUE(by_extent.Reaches(Vec2(2.2, 0.0), 1.5));
  EXPECT_FALSE(by_extent.Reaches(Vec2(3.5, 0.0), 1.5));
}

TEST(GridLocalMap, AJuvenilesUpdateLeavesTheGridAlone) {
  const std::vector<sim::Wall> walls = RoomWalls();
  FakeWallScanner scanner(walls, FrontLaser(), 4);
  GridLocalMap map;
  map.Update(scanner.Scan(Pose2{}), true);
  const int cells = map.Grid().known_cells();
  ASSERT_GT(cells, 0);
  map.Predict(Pose2{1.0, 0.0, 0.3});
  map.Update(scanner.Scan(Pose2{1.0, 0.0, 0.3}), false);
  EXPECT_EQ(map.Grid().known_cells(), cells);
  EXPECT_EQ(map.Complexity(), 1);
  EXPECT_TRUE(map.LastUpdateMatched()) << ToString(map.LastAlignment().outcome);
}

// Points() are the occupied cells' centres: on the walls the scans saw, and at most as many as
// asked for, spread over all of them.
TEST(GridLocalMap, PointsAreTheOccupiedCellsOnTheWalls) {
  const std::vector<sim::Wall> walls = RoomWalls();
  FakeWallScanner scanner(walls, FrontLaser(), 5);
  GridLocalMap map;
  map.Update(scanner.Scan(Pose2{}), true);
  const std::vector<Vec2> all = map.Points(100000);
  ASSERT_GT(all.size(), 150u);  // the east wall alone is 5 m of 5 cm cells
  double min_y = 0, max_y = 0;
  for (const Vec2& p : all) {
    EXPECT_LT(DistanceToWalls(p, walls), 0.06) << p.transpose();
    EXPECT_GT(p.x(), -0.1) << p.transpose();  // the laser looks along +x
    if (std::abs(p.x() - 5.0) < 0.06) {
      min_y = std::min(min_y, p.y());
      max_y = std::max(max_y, p.y());
    }
  }
  EXPECT_LT(min_y, -3.5);  // the east wall from the south-east corner
  EXPECT_GT(max_y, 0.8);   // to the alcove
  const std::vector<Vec2> some = map.Points(40);
  ASSERT_EQ(some.size(), 40u);
  for (const Vec2& p : some)
    EXPECT_NE(std::find(all.begin(), all.end(), p), all.end()) << p.transpose();
  EXPECT_EQ(some.front(), all.front());
  EXPECT_GT((some.back() - some.front()).norm(), 5.0);  // spread over the walls, not one run
  EXPECT_TRUE(GridLocalMap().Points(100).empty());
}

// 2 m across RoomWalls(), turning 1 rad.
std::vector<Pose2> TurningDrive() {
  std::vector<Pose2> truth;
  for (int k = 0; k <= 20; ++k) truth.push_back(Pose2{-2.0 + 0.1 * k, 0.0, 0.05 * k});
  return truth;
}

TEST(GridLocalMap, SerializesAndRefusesOtherBytes) {
  const std::vector<sim::Wall> walls = RoomWalls();
  const std::vector<Pose2> truth = TurningDrive();
  GridLocalMap map;
  Pose2 odometry;
  Drive(&map, walls, truth, 1.0, 0.0, &odometry);
  const std::string image = map.Serialize();
  GridLocalMap copy;
  ASSERT_TRUE(copy.Deserialize(image));
  EXPECT_EQ(copy.Grid().known_cells(), map.Grid().known_cells());
  EXPECT_EQ(copy.Complexity(), map.Complexity());
  EXPECT_NEAR(copy.RobotPose().mean.x, map.RobotPose().mean.x, 1e-12);
  // The same cells hold the same values: both score a scan alike.
  const std::vector<Vec2> points =
      map.AlignmentPoints(FakeWallScanner(walls, FrontLaser(), 6).Scan(truth.back()));
  EXPECT_EQ(copy.ExplainedPoints(points, truth.back()), map.ExplainedPoints(points, truth.back()));
  EXPECT_FALSE(copy.Deserialize(image.substr(0, image.size() - 1)));
  EXPECT_FALSE(copy.Deserialize("not a map"));
  EXPECT_EQ(copy.Serialize(), copy.Serialize());
}

// The image ends with the grid's window (width, height) and its values row by row, written in
// one block: the same bytes as one ByteWriter::Put per value. A value above kMaxValue is
// refused.
TEST(GridLocalMap, ImageHoldsTheValuesAsOnePutEach) {
  GridLocalMap map;
  Pose2 odometry;
  Drive(&map, RoomWalls(), TurningDrive(), 1.0, 0.0, &odometry);
  const ProbabilityGrid& grid = map.Grid();
  ASSERT_GT(grid.known_cells(), 1000);
  const std::string image = map.Serialize();
  ByteWriter old;
  old.Put<int32_t>(grid.limits().width);
  old.Put<int32_t>(grid.limits().height);
  for (uint16_t v : grid.values()) old.Put(v);
  ASSERT_GT(image.size(), old.bytes().size());
  const size_t block = image.size() - old.bytes().size();
  EXPECT_TRUE(image.compare(block, std::string::npos, old.bytes()) == 0);

  // Read back, the map is the one written, its grid's window included.
  GridLocalMap copy;
  ASSERT_TRUE(copy.Deserialize(image));
  EXPECT_TRUE(copy.Serialize() == image);
  EXPECT_EQ(copy.Grid().known_cells(), grid.known_cells());
  std::string bad = image;
  const uint16_t too_large = ProbabilityGrid::kMaxValue + 1;
  std::memcpy(bad.data() + bad.size() - sizeof(too_large), &too_large, sizeof(too_large));
  EXPECT_FALSE(copy.Deserialize(bad));
}

}  // namespace
}  // namespace atlas
