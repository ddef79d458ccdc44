#include "core/grid/interpolated_grid.h"

#include <gtest/gtest.h>

#include <random>

namespace atlas {
namespace {

// A fixed 2 x 2 m grid of random probabilities.
ProbabilityGrid RandomGrid(uint64_t seed) {
  ProbabilityGridOptions o;
  o.resolution = 0.1;
  ProbabilityGrid grid(o, Vec2(0.0, 0.0), Vec2(1.99, 1.99));
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<double> p(0.1, 0.9);
  for (uint16_t& v : grid.mutable_values()) v = grid.ValueOfProbability(p(rng));
  return grid;
}

TEST(InterpolatedGrid, PassesThroughTheCellCentres) {
  const ProbabilityGrid grid = RandomGrid(1);
  const InterpolatedGrid map(grid);
  for (int j = 0; j < 20; ++j) {
    for (int i = 0; i < 20; ++i) {
      const CellIndex c{i, j};
      EXPECT_NEAR(map.Evaluate(grid.limits().CenterOf(c), nullptr), grid.Probability(c), 1e-12);
    }
  }
}

TEST(InterpolatedGrid, GradientMatchesFiniteDifferencesAndIsContinuous) {
  const ProbabilityGrid grid = RandomGrid(2);
  const InterpolatedGrid map(grid);
  std::mt19937_64 rng(3);
  std::uniform_real_distribution<double> u(0.3, 1.7);
  const double h = 1e-6;
  for (int k = 0; k < 200; ++k) {
    const Vec2 p(u(rng), u(rng));
    Vec2 gradient;
    map.Evaluate(p, &gradient);
    const double dx =
        (map.Evaluate(p + Vec2(h, 0), nullptr) - map.Evaluate(p - Vec2(h, 0), nullptr)) / (2 * h);
    const double dy =
        (map.Evaluate(p + Vec2(0, h), nullptr) - map.Evaluate(p - Vec2(0, h), nullptr)) / (2 * h);
    EXPECT_NEAR(gradient.x(), dx, 1e-5);
    EXPECT_NEAR(gradient.y(), dy, 1e-5);
  }
  // Across a patch boundary (the line through the cell centres x = 0.95): value and gradient
  // agree on both sides.
  Vec2 left, right;
  const double a = map.Evaluate(Vec2(0.95 - 1e-9, 0.72), &left);
  const double b = map.Evaluate(Vec2(0.95 + 1e-9, 0.72), &right);
  EXPECT_NEAR(a, b, 1e-8);
  EXPECT_NEAR(left.x(), right.x(), 1e-6);
  EXPECT_NEAR(left.y(), right.y(), 1e-6);
}

TEST(InterpolatedGrid, UnknownAndOutsideScoreTheMinimum) {
  ProbabilityGridOptions o;
  const ProbabilityGrid grid(o, Vec2(0.0, 0.0), Vec2(0.99, 0.99));
  const InterpolatedGrid map(grid);
  Vec2 gradient;
  EXPECT_NEAR(map.Evaluate(Vec2(0.5, 0.5), &gradient), o.min_probability, 1e-12);
  EXPECT_NEAR(gradient.norm(), 0.0, 1e-12);
  EXPECT_NEAR(map.Evaluate(Vec2(-5.0, 7.0), nullptr), o.min_probability, 1e-12);
}

}  // namespace
}  // namespace atlas
