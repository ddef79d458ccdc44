#include "sim/ray_caster.h"

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <random>

#include "sim/building_generator.h"

namespace atlas::sim {
namespace {

// A 10 x 6 m room with a diagonal wall across its upper-right corner.
std::vector<Wall> Room() {
  return {{Vec2(0, 0), Vec2(10, 0)},
          {Vec2(10, 0), Vec2(10, 6)},
          {Vec2(10, 6), Vec2(0, 6)},
          {Vec2(0, 6), Vec2(0, 0)},
          {Vec2(7, 6), Vec2(10, 3)}};
}

TEST(RayCaster, HitsKnownWallsAtKnownRanges) {
  const RayCaster c(Room(), 1.0);
  const Vec2 o(2, 3);
  RayHit h = c.Cast(o, Vec2(-1, 0), 50);
  EXPECT_NEAR(h.range, 2.0, 1e-12);
  EXPECT_EQ(h.wall, 3);
  h = c.Cast(o, Vec2(0, 1), 50);
  EXPECT_NEAR(h.range, 3.0, 1e-12);
  EXPECT_EQ(h.wall, 2);
  h = c.Cast(o, Vec2(0, -2), 50);  // direction need not be unit length
  EXPECT_NEAR(h.range, 3.0, 1e-12);
  EXPECT_EQ(h.wall, 0);
  // Along y = 3 to the right: the diagonal x + y = 13 at x = 10, before the wall at x = 10
  // (both meet there); from (2, 4) it is at x = 9: range 7.
  h = c.Cast(Vec2(2, 4), Vec2(1, 0), 50);
  EXPECT_NEAR(h.range, 7.0, 1e-12);
  EXPECT_EQ(h.wall, 4);
  // At 45 degrees from (2, 3): meets the top wall at (5, 6), range 3 sqrt 2.
  h = c.Cast(o, Vec2(1, 1), 50);
  EXPECT_NEAR(h.range, 3.0 * std::numbers::sqrt2, 1e-12);
}

TEST(RayCaster, MaxRangeAndEmptySpaceGiveNoHit) {
  const RayCaster c(Room(), 1.0);
  const RayHit h = c.Cast(Vec2(2, 3), Vec2(-1, 0), 1.5);
  EXPECT_FALSE(h.hit());
  EXPECT_EQ(h.range, 1.5);
  const RayCaster lonely({{Vec2(0, 0), Vec2(1, 0)}}, 1.0);
  EXPECT_FALSE(lonely.Cast(Vec2(0.5, 1), Vec2(0, 1), 100).hit());   // pointing away
  EXPECT_TRUE(lonely.Cast(Vec2(0.5, 50), Vec2(0, -1), 100).hit());  // from outside the grid
  EXPECT_NEAR(lonely.Cast(Vec2(0.5, 50), Vec2(0, -1), 100).range, 50.0, 1e-12);
  EXPECT_FALSE(lonely.Cast(Vec2(5, 50), Vec2(0, -1), 100).hit());  // passes beside it
  const RayCaster none({}, 1.0);
  EXPECT_FALSE(none.Cast(Vec2(0, 0), Vec2(1, 0), 10).hit());
}

TEST(RayCaster, GridAgreesWithBruteForceInAGeneratedBuilding) {
  BuildingOptions o;
  o.min_rooms = 60;
  const World w = GenerateBuilding(o, 5);
  const Bounds b = WorldBounds(w);
  for (double cell : {0.5, 1.0, 3.0}) {
    const RayCaster c(w.walls, cell);
    std::mt19937_64 rng(9);
    std::uniform_real_distribution<double> ux(b.min.x() - 5, b.max.x() + 5),
        uy(b.min.y() - 5, b.max.y() + 5), ua(-std::numbers::pi, std::numbers::pi);
    int hits = 0;
    for (int i = 0; i < 5000; ++i) {
      const Vec2 o2(ux(rng), uy(rng));
      const double a = ua(rng);
      const Vec2 d(std::cos(a), std::sin(a));
      const RayHit g = c.Cast(o2, d, 40.0), f = c.CastBruteForce(o2, d, 40.0);
      ASSERT_EQ(g.hit(), f.hit()) << "ray " << i << " cell " << cell;
      ASSERT_NEAR(g.range, f.range, 1e-9) << "ray " << i << " cell " << cell;
      hits += g.hit();
    }
    EXPECT_GT(hits, 3500);
  }
}

}  // namespace
}  // namespace atlas::sim
