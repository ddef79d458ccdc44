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

// A stack built in slices of a few rows holds the same levels as one built at once (and as
// the block maxima of level 0), and no slice fills much more than asked; also for a grid
// narrower than the top level's blocks.
TEST(PrecomputationGrid, SlicedBuildEqualsTheWholeBuild) {
  for (const Vec2& size : {Vec2(3.09, 2.19), Vec2(0.19, 0.29)}) {  // 31 x 22, 2 x 3 cells
    ProbabilityGridOptions o;
    o.resolution = 0.1;
    ProbabilityGrid grid(o, Vec2(0.0, 0.0), size);
    const int w0 = grid.limits().width, h0 = grid.limits().height;
    std::mt19937_64 rng(11);
    std::uniform_real_distribution<double> p(0.0, 1.0);
    for (uint16_t& v : grid.mutable_values()) {
      v = p(rng) < 0.3 ? ProbabilityGrid::kUnknown : grid.ValueOfProbability(p(rng));
    }
    const PrecomputationGridStack whole(grid, 5);
    PrecomputationGridStack sliced(grid, 5, PrecomputationGridStack::Building::kInSlices);
    EXPECT_FALSE(sliced.complete());
    int slices = 0;
    while (!sliced.complete()) {
      const int64_t filled = sliced.Build(100);
      EXPECT_GT(filled, 0);
      EXPECT_LE(filled, 100 + w0 + 15);  // whole rows: at most one row of the widest level over
      ++slices;
    }
    EXPECT_GT(slices, 1);
    EXPECT_EQ(sliced.Build(100), 0);
    ASSERT_EQ(sliced.depth(), whole.depth());
    for (int k = 0; k < 5; ++k) {
      const int w = 1 << k;
      for (int y = -w - 1; y < h0 + 1; ++y) {
        for (int x = -w - 1; x < w0 + 1; ++x) {
          int most = 0;
          for (int b = y; b < y + w; ++b) {
            for (int a = x; a < x + w; ++a)
              most = std::max<int>(most, whole.Level(0).At(CellIndex{a, b}));
          }
          ASSERT_EQ(whole.Level(k).At(CellIndex{x, y}), most) << k << " " << x << " " << y;
          ASSERT_EQ(sliced.Level(k).At(CellIndex{x, y}), most) << k << " " << x << " " << y;
        }
      }
    }
  }
}

}  // namespace
}  // namespace atlas
