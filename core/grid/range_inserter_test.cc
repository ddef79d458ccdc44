#include "core/grid/range_inserter.h"

#include <gtest/gtest.h>

#include <cmath>

#include "core/testing/grid_scenes.h"

namespace atlas {
namespace {

double Odds(double p) { return p / (1.0 - p); }
double FromOdds(double o) { return o / (1.0 + o); }

// A fixed 4 x 4 m grid of 5 cm cells around the origin, updated by single-beam scans.
class OneBeamTest : public ::testing::Test {
 protected:
  InsertionStats Insert(const Vec2& origin, std::vector<Vec2> returns) {
    scan_.origin = origin;
    scan_.returns = std::move(returns);
    return inserter_.Insert(scan_, &grid_);
  }
  double ProbabilityAt(const Vec2& p) const { return grid_.Probability(grid_.limits().CellOf(p)); }
  bool KnownAt(const Vec2& p) const { return grid_.IsKnown(grid_.limits().CellOf(p)); }

  const ProbabilityGridOptions options_;
  ProbabilityGrid grid_{options_, Vec2(-2.0, -2.0), Vec2(1.99, 1.99)};
  RangeInserter inserter_{options_};
  RangeScan scan_;
};

TEST_F(OneBeamTest, MarksItsReturnAndTheCellsBefore) {
  const InsertionStats stats = Insert(Vec2(0.01, 0.01), {Vec2(1.01, 0.01)});
  EXPECT_EQ(stats.returns_inserted, 1);
  EXPECT_EQ(stats.cells_updated, 21);  // 20 cells of 5 cm crossed, the return's cell
  EXPECT_NEAR(ProbabilityAt(Vec2(1.01, 0.01)), 0.55, 1e-4);
  for (double x = 0.01; x < 1.0; x += 0.05) EXPECT_NEAR(ProbabilityAt(Vec2(x, 0.01)), 0.49, 1e-4);
  EXPECT_FALSE(KnownAt(Vec2(1.06, 0.01)));
  EXPECT_FALSE(KnownAt(Vec2(0.5, 0.06)));
  EXPECT_EQ(grid_.known_cells(), 21);

  // Four more scans: the odds multiply, clamped at the bounds.
  for (int i = 0; i < 4; ++i) inserter_.Insert(scan_, &grid_);
  EXPECT_NEAR(ProbabilityAt(Vec2(1.01, 0.01)), FromOdds(std::pow(Odds(0.55), 5)), 1e-4);
  EXPECT_NEAR(ProbabilityAt(Vec2(0.5, 0.01)), FromOdds(std::pow(Odds(0.49), 5)), 1e-4);
  EXPECT_EQ(grid_.known_cells(), 21);
  for (int i = 0; i < 100; ++i) inserter_.Insert(scan_, &grid_);
  EXPECT_NEAR(ProbabilityAt(Vec2(1.01, 0.01)), 0.9, 1e-4);
  EXPECT_NEAR(ProbabilityAt(Vec2(0.5, 0.01)), 0.1, 1e-4);
}

TEST_F(OneBeamTest, EachCellIsUpdatedOnceAScanAndHitsWin) {
  // Two returns in one cell, and a longer beam through that cell.
  Insert(Vec2(0.01, 0.01), {Vec2(0.51, 0.01), Vec2(0.52, 0.02), Vec2(1.01, 0.01)});
  EXPECT_NEAR(ProbabilityAt(Vec2(0.51, 0.01)), 0.55, 1e-4);
  EXPECT_NEAR(ProbabilityAt(Vec2(0.26, 0.01)), 0.49, 1e-4);
}

TEST_F(OneBeamTest, DiagonalRaysLeaveNoGaps) {
  const Vec2 from(0.012, 0.013), to(1.3, 0.9);
  Insert(from, {to});
  // Every cell the segment passes through is known (sampled finely along it).
  for (double t = 0.0; t <= 1.0; t += 0.001) EXPECT_TRUE(KnownAt(from + t * (to - from))) << t;
  // Crossing cells of a supercover: 4-connected, one step per cell boundary.
  const CellIndex a = grid_.limits().CellOf(from), b = grid_.limits().CellOf(to);
  EXPECT_EQ(grid_.known_cells(), std::abs(b.x - a.x) + std::abs(b.y - a.y) + 1);
}

TEST(RangeInserter, BeamsWithoutReturnFreeSpaceUpToTheCapOnly) {
  GridOptions o;
  o.range.no_return_free_range = 1.0;
  LaserScan laser;
  laser.angle_min = 0.0f;
  laser.angle_increment = 0.5f;
  laser.max_range = 30.0f;
  laser.ranges = {kNoReturn, 2.0f, 80.0f, 0.05f};
  RangeScan scan;
  RangeScanFromLaser(laser, Pose2{1.0, 0.0, 0.0}, o.range, &scan);
  ASSERT_EQ(scan.returns.size(), 1u);  // 2.0; 80 m is beyond max_range, 0.05 below min_range
  ASSERT_EQ(scan.misses.size(), 2u);
  EXPECT_TRUE(scan.misses[0].isApprox(Vec2(2.0, 0.0)));

  ProbabilityGrid grid(o.grid);
  RangeInserter inserter(o.grid);
  inserter.Insert(scan, &grid);
  const GridLimits& l = grid.limits();
  EXPECT_NEAR(grid.Probability(l.CellOf(Vec2(1.9, 0.01))), 0.49, 1e-4);
  EXPECT_FALSE(grid.IsKnown(l.CellOf(Vec2(2.1, 0.01))));
}

TEST(RangeInserter, ReturnsBeyondTheCapAreDroppedAndTheirRaysClipped) {
  ProbabilityGridOptions o;
  o.initial_cells = 16;
  o.max_cells = 64;  // 3.2 m
  ProbabilityGrid grid(o);
  RangeInserter inserter(o);
  RangeScan scan;
  scan.origin = Vec2(0.0, 0.0);
  scan.returns = {Vec2(1.0, 0.0), Vec2(40.0, 0.3), Vec2(-0.5, -25.0)};
  const InsertionStats stats = inserter.Insert(scan, &grid);
  EXPECT_EQ(stats.returns_inserted, 1);
  EXPECT_EQ(stats.returns_outside, 2);
  EXPECT_EQ(grid.limits().width, 64);
  EXPECT_EQ(grid.limits().height, 64);
  EXPECT_LE(grid.values().capacity(), 64u * 64u);
  EXPECT_NEAR(grid.Probability(grid.limits().CellOf(Vec2(1.0, 0.0))), 0.55, 1e-4);
}

TEST(RangeInserter, ARoomIsMappedWithWallsOccupiedAndTheFloorFree) {
  const GridOptions o;
  const std::vector<sim::Wall> walls = RoomWalls();
  const ProbabilityGrid grid =
      ScannedGrid(walls, {Pose2{0, 0, 0}, Pose2{-3, -2, 1.0}, Pose2{3, 2, -2.0}}, o);
  const GridLimits& l = grid.limits();
  // The room (10 x 8 m, alcove to x = 6) fits; every wall cell seen is more likely occupied.
  EXPECT_LE(l.width, o.grid.max_cells);
  // Walls lie on cell boundaries: a wall point is occupied when a cell beside it is.
  int wall_cells = 0, occupied = 0;
  for (const sim::Wall& w : walls) {
    const double length = (w.b - w.a).norm();
    for (double s = 0.05; s < length - 0.05; s += 0.05) {
      const CellIndex c = l.CellOf(w.a + s / length * (w.b - w.a));
      double most = 0.0;
      bool known = false;
      for (int dy = -1; dy <= 1; ++dy) {
        for (int dx = -1; dx <= 1; ++dx) {
          const CellIndex n{c.x + dx, c.y + dy};
          known = known || grid.IsKnown(n);
          if (grid.IsKnown(n)) most = std::max(most, grid.Probability(n));
        }
      }
      wall_cells += known;
      occupied += most > 0.5;
    }
  }
  EXPECT_GT(wall_cells, 500);
  EXPECT_GT(occupied, 0.95 * wall_cells);
  // Open floor is free; outside the room is unknown.
  // Three scans, one miss each: odds(0.49)^3.
  EXPECT_NEAR(grid.Probability(l.CellOf(Vec2(0.0, -2.0))), 0.47, 0.001);
  EXPECT_NEAR(grid.Probability(l.CellOf(Vec2(-1.0, 3.0))), 0.47, 0.001);
  EXPECT_FALSE(grid.IsKnown(l.CellOf(Vec2(0.0, 5.0))));
  int known = 0;
  for (uint16_t v : grid.values()) known += v != ProbabilityGrid::kUnknown;
  EXPECT_EQ(known, grid.known_cells());
}

}  // namespace
}  // namespace atlas

namespace atlas {
namespace {

// A wall 1 m to the side, scanned by a 181-beam front laser: with min_incidence 20 degrees the
// returns beyond 1 / sin(20 deg) = 2.9 m along it (grazing) are left out, the others kept; a
// lone post's return (no neighbouring return) is kept whatever its incidence.
TEST(RangeScanFromLaser, GrazingReturnsAreLeftOutWithMinIncidence) {
  FakeLaserOptions laser;
  laser.beams = 181;
  laser.range_sigma = 0.0;
  FakeWallScanner scanner({{Vec2(-1, 1), Vec2(30, 1)}}, laser, 1);
  const LaserScan scan = scanner.Scan(Pose2{});
  RangeScanOptions all, steep;
  steep.min_incidence = 0.35;
  RangeScan a, s;
  RangeScanFromLaser(scan, Pose2{}, all, &a);
  RangeScanFromLaser(scan, Pose2{}, steep, &s);
  ASSERT_GT(a.returns.size(), s.returns.size());
  double farthest = 0.0;
  for (const Vec2& p : s.returns) farthest = std::max(farthest, p.x());
  EXPECT_LT(farthest, 1.0 / std::sin(0.35) + 0.1);
  EXPECT_GT(farthest, 2.5);
  int near = 0;
  for (const Vec2& p : a.returns) near += p.x() < 2.5 ? 1 : 0;
  EXPECT_GE(static_cast<int>(s.returns.size()), near);
  // Beams that were dropped are neither hits nor misses.
  EXPECT_EQ(s.misses.size(), a.misses.size());
  FakeWallScanner post({{Vec2(5.0, -0.01), Vec2(5.0, 0.01)}}, laser, 1);
  RangeScanFromLaser(post.Scan(Pose2{}), Pose2{}, steep, &s);
  EXPECT_EQ(s.returns.size(), 1u);
}

}  // namespace
}  // namespace atlas
