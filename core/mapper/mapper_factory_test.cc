#include "core/mapper/mapper_factory.h"

#include <gtest/gtest.h>

#include "core/testing/fake_sonar_ring.h"

namespace atlas {
namespace {

// With laser lines, atlasd's atlas doubles the Genesis edges' covariance and seeds traversal
// where the robot returns: in frames near the dominant one within return_radius of their
// origin, and in frames farther along the graph within the tighter return_far_radius
// (docs/design.md, "III-E. Traversal"). The sonar atlas keeps the paper's Genesis edge and has
// no return band (on the simulator's sonar atlases the band made the robot NEES and the false
// closures worse).
TEST(MapperFactory, LaserAtlasSeedsWhereTheRobotReturnsAndTheSonarAtlasDoesNot) {
  MapperSettings s;
  for (RangeSensors sensors : {RangeSensors::kLaser, RangeSensors::kBoth}) {
    s.sensors = sensors;
    if (sensors == RangeSensors::kBoth) s.sonar_ring = FakeSonarRing24();
    const AtlasOptions o = MakeAtlas(s)->Options();
    EXPECT_EQ(o.Validate(), "");
    EXPECT_GT(o.genesis_cov_scale, 1.0);
    EXPECT_GT(o.return_q, o.q_traverse);
    EXPECT_GT(o.return_far_radius, 0.0);
    EXPECT_LT(o.return_far_radius, o.return_radius);
    EXPECT_TRUE(o.points.enabled);  // frames keep their scans' points (map_match.h, "Points")
  }
  s.sensors = RangeSensors::kSonar;
  s.sonar_ring = FakeSonarRing24();
  const AtlasOptions o = MakeAtlas(s)->Options();
  EXPECT_EQ(o.genesis_cov_scale, AtlasOptions{}.genesis_cov_scale);
  EXPECT_LE(o.return_q, o.q_traverse);
  EXPECT_EQ(o.return_far_radius, 0.0);
  EXPECT_FALSE(o.points.enabled);
}

}  // namespace
}  // namespace atlas
