#include "core/gridmap/grid_map_matcher.h"

#include <gtest/gtest.h>

#include <cmath>

#include "core/gridmap/dense_search.h"
#include "core/testing/fake_wall_scanner.h"
#include "core/testing/grid_scenes.h"

namespace atlas {
namespace {

// A room (x in [-6, 0], y in [-4, 4], a pillar) opening at x = 0 into a dead end 2 m wide and
// 6 m deep along +x. A scan from inside the dead end looking along it sees only the dead end.
std::vector<sim::Wall> RoomAndDeadEnd() {
  return {
      {Vec2(0, -4), Vec2(0, -1)},         {Vec2(0, 1), Vec2(0, 4)},
      {Vec2(-6, -4), Vec2(-6, 4)},        {Vec2(-6, 4), Vec2(0, 4)},
      {Vec2(-6, -4), Vec2(0, -4)},        {Vec2(0, 1), Vec2(6, 1)},
      {Vec2(0, -1), Vec2(6, -1)},         {Vec2(6, -1), Vec2(6, 1)},
      {Vec2(-4, -2), Vec2(-3.6, -2)},     {Vec2(-3.6, -2), Vec2(-3.6, -1.6)},
      {Vec2(-3.6, -1.6), Vec2(-4, -1.6)}, {Vec2(-4, -1.6), Vec2(-4, -2)},
  };
}

// The same dead end, but a wall crosses the room at x = -2 where RoomAndDeadEnd is open.
std::vector<sim::Wall> RoomWithCrossWall() {
  std::vector<sim::Wall> w = RoomAndDeadEnd();
  w.push_back({Vec2(-2, -3), Vec2(-2, 3)});
  return w;
}

// Frames longer than the default extent, with the fake scanner's odometry noise (its walls are
// straight, its base small and well calibrated).
GridLocalMapOptions LongFrames() {
  GridLocalMapOptions o;
  o.max_extent = 100.0;
  o.odometry = FakeWallMapOptions().odometry;
  return o;
}

// A frame made by driving along y = `y` from x0 to x1 (heading +x, world = frame) with a
// full-circle laser, the last scan (the one map-matching searches for) from a 180-degree laser
// looking along the drive.
GridLocalMap FrameAlong(const std::vector<sim::Wall>& walls, double x0, double x1, double y,
                        uint64_t seed, const GridLocalMapOptions& o = LongFrames(),
                        double max_range = 30.0) {
  GridLocalMap map(o);
  FakeWallScanner around(walls, FullCircleLaser(361, max_range), seed);
  FakeWallScanner ahead(walls, FrontLaser(181, max_range), seed + 1);
  const double step = 0.2;
  const int steps = static_cast<int>(std::lround((x1 - x0) / step));
  Pose2 truth{x0, y, 0.0};
  map.ResetRobotPose(UncertainPose{truth, Mat3::Zero()});
  map.Update(around.Scan(truth), true);
  for (int k = 1; k <= steps; ++k) {
    truth = Compose(truth, Pose2{step, 0.0, 0.0});
    map.Predict(Pose2{step, 0.0, 0.0});
    map.Update(k == steps ? ahead.Scan(truth) : around.Scan(truth), true);
  }
  return map;
}

// The projected pose of B's frame in A's: 0.2 m and 0.03 rad off the truth (identity), 0.3 m
// and 0.05 rad sigma.
UncertainPose PriorNearIdentity() {
  UncertainPose p{Pose2{0.2, -0.1, 0.03}, Mat3::Zero()};
  p.cov.diagonal() = Vec3(0.09, 0.09, 0.0025);
  return p;
}

TEST(GridMapMatcher, AcceptsTheTruePlacementOfARevisitWholeOrInSlices) {
  const GridLocalMap a = FrameAlong(RoomAndDeadEnd(), -5.0, 3.0, 0.0, 1);
  const GridLocalMap b = FrameAlong(RoomAndDeadEnd(), -4.0, 4.0, 0.3, 11);
  const UncertainPose prior = PriorNearIdentity();
  const MapMatch m = GridMapMatcher(a.Options()).Match(a, b, &prior);
  ASSERT_EQ(m.result, MapMatchResult::kAccepted) << MapMatchReasonName(m.reason);
  EXPECT_EQ(m.reason, MapMatchReason::kMatched);
  // Within the 0.1 m and 0.03 rad that a match edge's covariance is given at least.
  EXPECT_NEAR(m.b_in_a.mean.x, 0.0, 0.1);
  EXPECT_NEAR(m.b_in_a.mean.y, 0.0, 0.1);
  EXPECT_NEAR(WrapAngle(m.b_in_a.mean.theta), 0.0, 0.03);
  // Each frame's walls lie where the other saw walls or nothing: no conflict either way.
  const FreeSpaceConflict ba =
      FreeSpaceConflictOf(a.Grid(), b.Grid(), m.b_in_a.mean, Vec2(3.0, 0.0), kFreeSpaceRadius);
  EXPECT_GT(ba.occupied, 200);
  EXPECT_LT(ba.Fraction(), 0.01);

  // In slices of a small work bound the search takes many steps and ends with the same
  // placement: the slicing changes when, not what.
  GridLocalMapOptions small = a.Options();
  small.match.work_per_step = 20000;
  const GridMapMatcher matcher(small);
  const std::unique_ptr<MapMatchSearch> search = matcher.Begin(a, b, &prior);
  int slices = 1;
  while (!search->Continue(a, b)) ++slices;
  EXPECT_GT(slices, 20);
  const MapMatch& sliced = search->Result();
  ASSERT_EQ(sliced.result, MapMatchResult::kAccepted) << MapMatchReasonName(sliced.reason);
  EXPECT_EQ(sliced.hypotheses, m.hypotheses);
  EXPECT_DOUBLE_EQ(sliced.b_in_a.mean.x, m.b_in_a.mean.x);
  EXPECT_DOUBLE_EQ(sliced.b_in_a.mean.y, m.b_in_a.mean.y);
  EXPECT_DOUBLE_EQ(sliced.b_in_a.mean.theta, m.b_in_a.mean.theta);
  EXPECT_TRUE(search->Continue(a, b));  // finished stays finished
  // No prior: nothing to search, finished at once.
  EXPECT_TRUE(matcher.Begin(a, b, nullptr)->Continue(a, b));
}

// B's frame is another place whose dead end looks the same, but B holds a wall across space A
// has seen through. A's last scan (of the dead end) fits B as well as it fits the true place,
// so only the free space tells them apart.
TEST(GridMapMatcher, RefusesBsWallsInAsObservedFreeSpace) {
  const GridLocalMap a = FrameAlong(RoomAndDeadEnd(), -5.0, 3.0, 0.0, 1);
  const GridLocalMap b = FrameAlong(RoomWithCrossWall(), -1.4, 4.0, 0.3, 11);
  const UncertainPose prior = PriorNearIdentity();
  const MapMatch m = GridMapMatcher(a.Options()).Match(a, b, &prior);
  EXPECT_EQ(m.result, MapMatchResult::kRejected);
  EXPECT_EQ(m.reason, MapMatchReason::kFreeSpace) << MapMatchReasonName(m.reason);
  // The cross wall, 5 m behind the robot, is in A's free space; A's walls are not in B's.
  const FreeSpaceConflict ba =
      FreeSpaceConflictOf(a.Grid(), b.Grid(), Pose2{}, Vec2(3.0, 0.0), kFreeSpaceRadius);
  EXPECT_GT(ba.Fraction(), 0.1);
  const FreeSpaceConflict ab =
      FreeSpaceConflictOf(b.Grid(), a.Grid(), Pose2{}, Vec2(3.0, 0.0), kFreeSpaceRadius);
  EXPECT_LT(ab.Fraction(), 0.02);
  // Without the test the same search accepts the placement: the scan alone cannot tell.
  GridLocalMapOptions off = a.Options();
  off.max_free_space_conflict = 1.0;
  const MapMatch blind = GridMapMatcher(off).Match(a, b, &prior);
  ASSERT_EQ(blind.result, MapMatchResult::kAccepted) << MapMatchReasonName(blind.reason);
  EXPECT_NEAR(blind.b_in_a.mean.x, 0.0, 0.1);
}

// The other way round: A's own walls stand where B has seen through.
TEST(GridMapMatcher, RefusesAsWallsInBsObservedFreeSpace) {
  const GridLocalMap a = FrameAlong(RoomWithCrossWall(), -1.4, 3.0, 0.0, 1);
  const GridLocalMap b = FrameAlong(RoomAndDeadEnd(), -5.0, 4.0, 0.3, 11);
  const UncertainPose prior = PriorNearIdentity();
  const MapMatch m = GridMapMatcher(a.Options()).Match(a, b, &prior);
  EXPECT_EQ(m.result, MapMatchResult::kRejected);
  EXPECT_EQ(m.reason, MapMatchReason::kFreeSpace) << MapMatchReasonName(m.reason);
  const FreeSpaceConflict ab =
      FreeSpaceConflictOf(b.Grid(), a.Grid(), Pose2{}, Vec2(3.0, 0.0), kFreeSpaceRadius);
  EXPECT_GT(ab.Fraction(), 0.1);
}

// A corridor 3 m wide along x (-30 to 30 m) with a door recess 1.5 m wide and 1 m deep in
// both walls at each of `doors`.
std::vector<sim::Wall> CorridorWithDoors(const std::vector<double>& doors) {
  std::vector<sim::Wall> w;
  for (double side : {-1.0, 1.0}) {
    const double y = 1.5 * side, back = 2.5 * side;
    double x = -30.0;
    for (double d : doors) {
      w.push_back({Vec2(x, y), Vec2(d - 0.75, y)});
      w.push_back({Vec2(d - 0.75, y), Vec2(d - 0.75, back)});
      w.push_back({Vec2(d - 0.75, back), Vec2(d + 0.75, back)});
      w.push_back({Vec2(d + 0.75, back), Vec2(d + 0.75, y)});
      x = d + 0.75;
    }
    w.push_back({Vec2(x, y), Vec2(30, y)});
  }
  return w;
}

// B's frame in A's is the identity, 0.2 m off the prior's mean along the corridor; the prior's
// sigma along it is `sigma_x` (0.3 m across, 0.05 rad).
UncertainPose PriorAlongCorridor(double sigma_x) {
  UncertainPose p{Pose2{0.2, -0.1, 0.03}, Mat3::Zero()};
  p.cov.diagonal() = Vec3(sigma_x * sigma_x, 0.09, 0.0025);
  return p;
}

// Doors every 4 m, a laser of 8 m: A's last scan fits B as well 4 m further on. The match's
// window (3 m either side at most) does not reach that far; the prior's 3 sigma does when its
// sigma along the corridor is 1.5 m, and then the placement cannot be told apart.
TEST(GridMapMatcher, RefusesARepetitionThePriorAllowsBeyondTheWindow) {
  const std::vector<sim::Wall> walls = CorridorWithDoors({-16, -12, -8, -4, 0, 4, 8, 12, 16});
  const GridLocalMap a = FrameAlong(walls, -3.0, 3.0, 0.0, 1, LongFrames(), 8.0);
  const GridLocalMap b = FrameAlong(walls, -8.0, 8.0, 0.3, 11, LongFrames(), 8.0);
  ASSERT_EQ(a.Options().match.max_linear_window, 3.0);
  ASSERT_EQ(a.Options().match.max_repetition_window, 8.0);

  const UncertainPose narrow = PriorAlongCorridor(0.3);  // 3 sigma inside the window
  const MapMatch known = GridMapMatcher(a.Options()).Match(a, b, &narrow);
  ASSERT_EQ(known.result, MapMatchResult::kAccepted) << MapMatchReasonName(known.reason);
  EXPECT_NEAR(known.b_in_a.mean.x, 0.0, 0.1);

  const UncertainPose wide = PriorAlongCorridor(1.5);  // 3 sigma 4.5 m: the next door
  const MapMatch lost = GridMapMatcher(a.Options()).Match(a, b, &wide);
  EXPECT_EQ(lost.result, MapMatchResult::kAmbiguous);
  EXPECT_EQ(lost.reason, MapMatchReason::kRepetitive) << MapMatchReasonName(lost.reason);

  // The same search without the look beyond the window accepts the placement in the window.
  GridLocalMapOptions off = a.Options();
  off.match.max_repetition_window = off.match.max_linear_window;
  const MapMatch blind = GridMapMatcher(off).Match(a, b, &wide);
  ASSERT_EQ(blind.result, MapMatchResult::kAccepted) << MapMatchReasonName(blind.reason);
  EXPECT_NEAR(blind.b_in_a.mean.x, 0.0, 0.1);

  // Sliced, the look beyond the window ends the same way.
  GridLocalMapOptions small = a.Options();
  small.match.work_per_step = 20000;
  const GridMapMatcher sliced_matcher(small);
  const std::unique_ptr<MapMatchSearch> search = sliced_matcher.Begin(a, b, &wide);
  while (!search->Continue(a, b)) {
  }
  EXPECT_EQ(search->Result().reason, MapMatchReason::kRepetitive)
      << MapMatchReasonName(search->Result().reason);
  EXPECT_EQ(search->Result().hypotheses, lost.hypotheses);
}

// Doors at irregular spacing: with the same wide prior no other placement fits, and the match
// is accepted.
TEST(GridMapMatcher, AcceptsWithAWidePriorWhenNothingRepeats) {
  const std::vector<sim::Wall> walls = CorridorWithDoors({-13, -6, 4.5, 9.8});
  const GridLocalMap a = FrameAlong(walls, -3.0, 3.0, 0.0, 1, LongFrames(), 8.0);
  const GridLocalMap b = FrameAlong(walls, -8.0, 8.0, 0.3, 11, LongFrames(), 8.0);
  const UncertainPose wide = PriorAlongCorridor(1.5);
  const MapMatch m = GridMapMatcher(a.Options()).Match(a, b, &wide);
  ASSERT_EQ(m.result, MapMatchResult::kAccepted) << MapMatchReasonName(m.reason);
  EXPECT_NEAR(m.b_in_a.mean.x, 0.0, 0.1);
  EXPECT_NEAR(m.b_in_a.mean.y, 0.0, 0.1);
}

// Far points are not searched for: they set the heading step (a cell at the farthest point).
TEST(SearchPoints, KeepsThePointsNearTheRobotEvenlySubsampled) {
  std::vector<Vec2> points;
  for (int i = 0; i < 10; ++i) points.push_back(Vec2(i, 0.0));  // 0 .. 9 m
  points.push_back(Vec2(3.0, 4.0));                             // 5 m: kept
  points.push_back(Vec2(3.0, 4.1));                             // beyond
  GridSearchOptions o;
  o.max_point_range = 5.0;
  o.max_points = 100;
  const std::vector<Vec2> near = SearchPoints(points, o);
  ASSERT_EQ(near.size(), 7u);  // 0 .. 5 m on the axis, and (3, 4)
  for (const Vec2& p : near) EXPECT_LE(p.norm(), 5.0);
  EXPECT_EQ(near.back(), Vec2(3.0, 4.0));
  o.max_points = 3;
  const std::vector<Vec2> few = SearchPoints(points, o);
  ASSERT_EQ(few.size(), 3u);
  EXPECT_EQ(few[0], near[0]);
  for (const Vec2& p : few) EXPECT_LE(p.norm(), 5.0);
  o.max_point_range = 0.0;
  EXPECT_NE(o.Validate(), "");
}

TEST(GridMapMatcher, FreeSpaceConflictOptionIsValidated) {
  GridLocalMapOptions o;
  EXPECT_EQ(o.Validate(), "");
  o.max_free_space_conflict = -0.1;
  EXPECT_NE(o.Validate(), "");
  o.max_free_space_conflict = 1.5;
  EXPECT_NE(o.Validate(), "");
  o.max_free_space_conflict = 1.0;  // 1: the test never refuses
  EXPECT_EQ(o.Validate(), "");
  o.match.max_repetition_window = -1.0;
  EXPECT_NE(o.Validate(), "");
  o.match.max_repetition_window = 0.0;  // at most the window: no look beyond it
  EXPECT_EQ(o.Validate(), "");
}

}  // namespace
}  // namespace atlas
