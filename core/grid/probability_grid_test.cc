#include "core/grid/probability_grid.h"

#include <gtest/gtest.h>

#include <cstdint>
#include <vector>

namespace atlas {
namespace {

ProbabilityGridOptions SmallOptions() {
  ProbabilityGridOptions o;
  o.resolution = 0.1;
  o.initial_cells = 8;
  o.max_cells = 64;
  return o;
}

TEST(GridLimits, CellsLieOnOneGlobalLattice) {
  GridLimits l;
  l.resolution = 0.1;
  l.offset = CellIndex{-5, 3};
  l.width = l.height = 10;
  EXPECT_EQ(l.CellOf(Vec2(-0.45, 0.35)), (CellIndex{0, 0}));
  EXPECT_EQ(l.CellOf(Vec2(-0.55, 0.35)), (CellIndex{-1, 0}));
  EXPECT_TRUE(l.CenterOf(CellIndex{0, 0}).isApprox(Vec2(-0.45, 0.35)));
  EXPECT_TRUE(l.Contains(CellIndex{9, 9}));
  EXPECT_FALSE(l.Contains(CellIndex{10, 0}));
}

TEST(ProbabilityGrid, ValuesAndProbabilitiesConvert) {
  const ProbabilityGrid grid(SmallOptions());
  EXPECT_EQ(grid.ValueOfProbability(0.0), 1);
  EXPECT_EQ(grid.ValueOfProbability(1.0), ProbabilityGrid::kMaxValue);
  EXPECT_DOUBLE_EQ(grid.ProbabilityOfValue(ProbabilityGrid::kUnknown), 0.1);
  for (double p : {0.1, 0.3, 0.5, 0.55, 0.9}) {
    EXPECT_NEAR(grid.ProbabilityOfValue(grid.ValueOfProbability(p)), p, 2e-5);
  }
}

TEST(ProbabilityGrid, GrowingKeepsEveryValueInItsCell) {
  ProbabilityGrid grid(SmallOptions());
  EXPECT_EQ(grid.limits().width, 0);
  ASSERT_TRUE(grid.GrowToCover(Vec2(0.0, 0.0), Vec2(0.2, 0.2)));
  EXPECT_EQ(grid.limits().width, 8);
  const Vec2 p(0.15, 0.05);
  const CellIndex c = grid.limits().CellOf(p);
  grid.mutable_values()[grid.limits().IndexOf(c)] = 1234;
  ASSERT_TRUE(grid.GrowToCover(Vec2(-1.5, -0.1), Vec2(0.1, 2.0)));
  EXPECT_GE(grid.limits().width, 16);
  EXPECT_EQ(grid.Value(grid.limits().CellOf(p)), 1234);
  EXPECT_TRUE(grid.limits().Contains(grid.limits().CellOf(Vec2(-1.5, 2.0))));
  int set = 0;
  for (uint16_t v : grid.values()) set += v != 0;
  EXPECT_EQ(set, 1);
}

TEST(ProbabilityGrid, NeverExceedsItsCap) {
  ProbabilityGrid grid(SmallOptions());
  ASSERT_TRUE(grid.GrowToCover(Vec2(0.0, 0.0), Vec2(0.1, 0.1)));
  // 100 m away: beyond 64 cells of 0.1 m.
  EXPECT_FALSE(grid.GrowToCover(Vec2(0.0, 0.0), Vec2(100.0, 0.1)));
  EXPECT_EQ(grid.limits().width, 64);
  EXPECT_LE(grid.limits().height, 64);
  EXPECT_TRUE(grid.limits().Contains(grid.limits().CellOf(Vec2(0.0, 0.0))));
  EXPECT_FALSE(grid.GrowToCover(Vec2(-100.0, -100.0), Vec2(0.0, 0.0)));
  EXPECT_EQ(grid.limits().width, 64);
  EXPECT_EQ(grid.limits().height, 64);
  EXPECT_LE(grid.values().capacity(), 64u * 64u);
}

// A saved window and its values restore exactly into a fresh growing grid, which grows on from
// there; a window beyond the cap or the lattice, values of another size or above kMaxValue, or
// a grid with fixed bounds are refused and change nothing.
TEST(ProbabilityGrid, RestoresASavedWindowExactly) {
  ProbabilityGrid grid(SmallOptions());
  ASSERT_TRUE(grid.GrowToCover(Vec2(0.0, 0.0), Vec2(0.2, 0.2)));
  grid.mutable_values()[3] = 1234;
  grid.mutable_values()[10] = ProbabilityGrid::kMaxValue;
  grid.AddKnownCells(2);
  ASSERT_TRUE(grid.GrowToCover(Vec2(-1.5, -0.1), Vec2(0.1, 2.0)));
  const GridLimits& l = grid.limits();

  ProbabilityGrid restored(SmallOptions());
  ASSERT_TRUE(restored.Restore(l.offset, l.width, l.height, grid.values()));
  EXPECT_EQ(restored.limits().offset, l.offset);
  EXPECT_EQ(restored.limits().width, l.width);
  EXPECT_EQ(restored.limits().height, l.height);
  EXPECT_EQ(restored.values(), grid.values());
  EXPECT_EQ(restored.known_cells(), 2);
  ASSERT_TRUE(grid.GrowToCover(Vec2(-3.0, -3.0), Vec2(0.0, 0.0)));
  ASSERT_TRUE(restored.GrowToCover(Vec2(-3.0, -3.0), Vec2(0.0, 0.0)));
  EXPECT_EQ(restored.limits().offset, grid.limits().offset);
  EXPECT_EQ(restored.values(), grid.values());

  const std::vector<uint16_t> four(4, 1);
  ProbabilityGrid fresh(SmallOptions());
  EXPECT_FALSE(fresh.Restore(CellIndex{0, 0}, 65, 1, std::vector<uint16_t>(65, 1)));
  EXPECT_FALSE(fresh.Restore(CellIndex{0, 0}, 0, 4, {}));
  EXPECT_FALSE(fresh.Restore(CellIndex{0, 0}, 2, 3, four));
  EXPECT_FALSE(fresh.Restore(CellIndex{ProbabilityGrid::kMaxCellIndex - 1, 0}, 2, 2, four));
  EXPECT_FALSE(fresh.Restore(CellIndex{0, -ProbabilityGrid::kMaxCellIndex - 1}, 2, 2, four));
  EXPECT_FALSE(fresh.Restore(CellIndex{0, 0}, 2, 2, {1, 1, ProbabilityGrid::kMaxValue + 1, 1}));
  EXPECT_EQ(fresh.limits().width, 0);
  EXPECT_EQ(fresh.known_cells(), 0);
  ProbabilityGrid fixed(SmallOptions(), Vec2(-1.0, -1.0), Vec2(0.95, 0.95));
  EXPECT_FALSE(fixed.Restore(CellIndex{0, 0}, 2, 2, four));
  EXPECT_TRUE(fresh.Restore(CellIndex{-7, 5}, 2, 2, four));
  EXPECT_EQ(fresh.known_cells(), 4);
}

TEST(ProbabilityGrid, FixedBoundsNeverGrow) {
  ProbabilityGrid grid(SmallOptions(), Vec2(-1.0, -1.0), Vec2(0.95, 0.95));
  EXPECT_FALSE(grid.grows());
  EXPECT_EQ(grid.limits().width, 20);
  EXPECT_EQ(grid.limits().height, 20);
  EXPECT_TRUE(grid.GrowToCover(Vec2(-0.5, -0.5), Vec2(0.5, 0.5)));
  EXPECT_FALSE(grid.GrowToCover(Vec2(-0.5, -0.5), Vec2(5.0, 0.5)));
  EXPECT_EQ(grid.limits().width, 20);
  EXPECT_EQ(grid.Value(CellIndex{25, 0}), ProbabilityGrid::kUnknown);
  EXPECT_DOUBLE_EQ(grid.Probability(CellIndex{-1, 0}), 0.1);
}

TEST(ProbabilityGrid, OccupiedCellCentersListsCellsAboveTheThreshold) {
  ProbabilityGrid grid(SmallOptions(), Vec2(0.0, 0.0), Vec2(0.95, 0.95));
  grid.mutable_values()[grid.limits().IndexOf(CellIndex{2, 3})] = grid.ValueOfProbability(0.8);
  grid.mutable_values()[grid.limits().IndexOf(CellIndex{4, 4})] = grid.ValueOfProbability(0.4);
  const std::vector<Vec2> points = OccupiedCellCenters(grid, 0.6);
  ASSERT_EQ(points.size(), 1u);
  EXPECT_TRUE(points[0].isApprox(Vec2(0.25, 0.35)));
}

}  // namespace
}  // namespace atlas
