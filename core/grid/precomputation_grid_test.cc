#include "core/grid/precomputation_grid.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <random>

namespace atlas {
namespace {

TEST(PrecomputationGrid, EachLevelIsTheMaximumOverItsBlock) {
  ProbabilityGridOptions o;
  o.resolution = 0.1;
  ProbabilityGrid grid(o, Vec2(0.0, 0.0), Vec2(2.29, 1.69));  // 23 x 17 cells
  std::mt19937_64 rng(7);
  std::uniform_real_distribution<double> p(0.0, 1.0);
  for (uint16_t& v : grid.mutable_values()) {
    v = p(rng) < 0.3 ? ProbabilityGrid::kUnknown : grid.ValueOfProbability(p(rng));
  }
  const PrecomputationGridStack stack(grid, 5);
  ASSERT_EQ(stack.depth(), 5);
  const PrecomputationGrid& level0 = stack.Level(0);
  for (int j = 0; j < 17; ++j) {
    for (int i = 0; i < 23; ++i) {
      const CellIndex c{i, j};
      const int expected =
          grid.IsKnown(c) ? static_cast<int>(std::lround(255.0 * (grid.Probability(c) - 0.1) / 0.8))
                          : 0;
      EXPECT_EQ(level0.At(c), expected);
    }
  }
  for (int k = 1; k < 5; ++k) {
    const PrecomputationGrid& level = stack.Level(k);
    const int w = 1 << k;
    EXPECT_EQ(level.width(), w);
    for (int y = -w - 2; y < 17 + 2; ++y) {
      for (int x = -w - 2; x < 23 + 2; ++x) {
        int most = 0;
        for (int b = y; b < y + w; ++b) {
          for (int a = x; a < x + w; ++a) most = std::max<int>(most, level0.At(CellIndex{a, b}));
        }
        ASSERT_EQ(level.At(CellIndex{x, y}), most) << k << " " << x << " " << y;
      }
    }
  }
  EXPECT_DOUBLE_EQ(stack.MeanProbability(255 * 4, 4), 0.9);
  EXPECT_DOUBLE_EQ(stack.MeanProbability(0, 4), 0.1);
}

}  // namespace
}  // namespace atlas
