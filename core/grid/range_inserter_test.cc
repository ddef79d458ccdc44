#include "core/grid/range_inserter.h"

#include <gtest/gtest.h>

#include <cmath>

#include "core/grid/grid_test_scenes.h"

namespace atlas {
namespace {

double Odds(double p) { return p / (1.0 - p); }
double FromOdds(double o) { return o / (1.0 + o); }

ProbabilityGrid FixedGrid(const ProbabilityGridOptions& o) {
  return ProbabilityGrid(o, Vec2(-2.0, -2.0), Vec2(1.99, 1.99));
}

TEST(RangeInserter, OneBeamMarksItsReturnAndTheCellsBefore) {
  const ProbabilityGridOptions o;
  ProbabilityGrid grid = FixedGrid(o);
  RangeInserter inserter(o);
  RangeScan scan;
  scan.origin = Vec2(0.01, 0.01);
  scan.returns = {Vec2(1.01, 0.01)};
  const InsertionStats stats = inserter.Insert(scan, &grid);
  EXPECT_EQ(stats.returns_inserted, 1);
  EXPECT_EQ(stats.cells_updated, 21);  // 20 cells of 5 cm crossed, the return's cell
  const GridLimits& l = grid.limits();
  EXPECT_NEAR(grid.Probability(l.CellOf(Vec2(1.01, 0.01))), 0.55, 1e-4);
  for (double x = 0.01; x < 1.0; x += 0.05) {
    EXPECT_NEAR(grid.Probability(l.CellOf(Vec2(x, 0.01))), 0.49, 1e-4) << x;
  }
  EXPECT_FALSE(grid.IsKnown(l.CellOf(Vec2(1.06, 0.01))));
  EXPECT_FALSE(grid.IsKnown(l.CellOf(Vec2(0.5, 0.06))));
  EXPECT_EQ(grid.known_cells(), 21);

  // Four more scans: the odds multiply, clamped at the bounds.
  for (int i = 0; i < 4; ++i) inserter.Insert(scan, &grid);
  EXPECT_NEAR(grid.Probability(l.CellOf(Vec2(1.01, 0.01))), FromOdds(std::pow(Odds(0.55), 5)),
              1e-4);
  EXPECT_NEAR(grid.Probability(l.CellOf(Vec2(0.5, 0.01))), FromOdds(std::pow(Odds(0.49), 5)), 1e-4);
  EXPECT_EQ(grid.known_cells(), 21);
  for (int i = 0; i < 100; ++i) inserter.Insert(scan, &grid);
  EXPECT_NEAR(grid.Probability(l.CellOf(Vec2(1.01, 0.01))), 0.9, 1e-4);
  EXPECT_NEAR(grid.Probability(l.CellOf(Vec2(0.5, 0.01))), 0.1, 1e-4);
}

TEST(RangeInserter, EachCellIsUpdatedOnceAScanAndHitsWin) {
  const ProbabilityGridOptions o;
  ProbabilityGrid grid = FixedGrid(o);
  RangeInserter inserter(o);
  RangeScan scan;
  scan.origin = Vec2(0.01, 0.01);
  // Two returns in one cell, and a longer beam through that cell.
  scan.returns = {Vec2(0.51, 0.01), Vec2(0.52, 0.02), Vec2(1.01, 0.01)};
  inserter.Insert(scan, &grid);
  const GridLimits& l = grid.limits();
  EXPECT_NEAR(grid.Probability(l.CellOf(Vec2(0.51, 0.01))), 0.55, 1e-4);
  EXPECT_NEAR(grid.Probability(l.CellOf(Vec2(0.26, 0.01))), 0.49, 1e-4);
}

TEST(RangeInserter, DiagonalRaysLeaveNoGaps) {
  const ProbabilityGridOptions o;
  ProbabilityGrid grid = FixedGrid(o);
  RangeInserter inserter(o);
  RangeScan scan;
  scan.origin = Vec2(0.012, 0.013);
  scan.returns = {Vec2(1.3, 0.9)};
  inserter.Insert(scan, &grid);
  // Every cell the segment passes through is known (sampled finely along it).
  for (double t = 0.0; t <= 1.0; t += 0.001) {
    const Vec2 p = scan.origin + t * (scan.returns[0] - scan.origin);
    EXPECT_TRUE(grid.IsKnown(grid.limits().CellOf(p))) << t;
  }
  // Crossing cells of a supercover: 4-connected, one step per cell boundary.
  const CellIndex a = grid.limits().CellOf(scan.origin), b = grid.limits().CellOf(scan.returns[0]);
  EXPECT_EQ(grid.known_cells(), std::abs(b.x - a.x) + std::abs(b.y - a.y) + 1);
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
  const std::vector<Wall> walls = RoomWalls();
  const ProbabilityGrid grid =
      ScannedGrid(walls, {Pose2{0, 0, 0}, Pose2{-3, -2, 1.0}, Pose2{3, 2, -2.0}}, o);
  const GridLimits& l = grid.limits();
  // The room (10 x 8 m, alcove to x = 6) fits; every wall cell seen is more likely occupied.
  EXPECT_LE(l.width, o.grid.max_cells);
  // Walls lie on cell boundaries: a wall point is occupied when a cell beside it is.
  int wall_cells = 0, occupied = 0;
  for (const Wall& w : walls) {
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
