#include "sim/corridor.h"

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "sim/ray_caster.h"

namespace atlas::sim {
namespace {

// The corridor is closed: every ray from a point on its centreline hits a wall no farther than
// the corridor's diagonal, and the pillar half way is seen from the centreline beside it.
TEST(CorridorWalls, ClosedWithThePillarHalfWay) {
  const double length = 20.0, width = 2.4;
  const std::vector<Wall> walls = CorridorWalls(length, width);
  const RayCaster caster(walls);
  const double diagonal = std::hypot(length + 2.0, width + 0.6);
  for (double x = 0.0; x <= length; x += 2.5) {
    for (int k = 0; k < 360; ++k) {
      const double a = k * std::numbers::pi / 180.0;
      const RayHit hit = caster.Cast(Vec2(x, 0.0), Vec2(std::cos(a), std::sin(a)), 100.0);
      ASSERT_TRUE(hit.hit()) << "x " << x << " ray " << k;
      EXPECT_LE(hit.range, diagonal);
    }
  }
  // Straight up from below the pillar's south face (y = h - 0.5): 0.7 m away.
  const RayHit up = caster.Cast(Vec2(0.5 * length + 0.2, 0.0), Vec2(0.0, 1.0), 10.0);
  ASSERT_TRUE(up.hit());
  EXPECT_NEAR(up.range, 0.5 * width - 0.5, 1e-12);
}

}  // namespace
}  // namespace atlas::sim
