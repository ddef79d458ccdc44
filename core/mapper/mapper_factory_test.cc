#include "core/mapper/mapper_factory.h"

#include <gtest/gtest.h>

#include "core/gridmap/grid_local_map.h"
#include "core/testing/fake_sonar_ring.h"
#include "core/testing/fake_wall_scanner.h"
#include "core/testing/grid_scenes.h"

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
  // The laser atlas is AtlasOptions' defaults: the factory fixes nothing of its own.
  EXPECT_TRUE(MakeAtlas(MapperSettings{})->Options() == AtlasOptions{});
  s.sensors = RangeSensors::kSonar;
  s.sonar_ring = FakeSonarRing24();
  const AtlasOptions o = MakeAtlas(s)->Options();
  EXPECT_EQ(o.genesis_cov_scale, 1.0);
  EXPECT_LE(o.return_q, o.q_traverse);
  EXPECT_EQ(o.return_far_radius, 0.0);
  EXPECT_FALSE(o.points.enabled);
}

// localmap.kind = "grid": the frames hold probability grids (no lines, no points) and the
// laser atlas's Genesis and return band stay; grids need the laser alone.
TEST(AtlasFactory, GridFramesHoldGridsWithTheLaserAlone) {
  MapperSettings s;
  s.grid_frames = true;
  EXPECT_EQ(ValidateMapperSettings(s), "");
  std::unique_ptr<Atlas> atlas = MakeAtlas(s);
  EXPECT_FALSE(atlas->Options().points.enabled);
  EXPECT_GT(atlas->Options().genesis_cov_scale, 1.0);
  FakeWallScanner scanner(RoomWalls(), FrontLaser(), 1);
  atlas->Step(Pose2{}, scanner.Scan(Pose2{}));
  atlas->Step(Pose2{0.3, 0.0, 0.0}, scanner.Scan(Pose2{0.3, 0.0, 0.0}));
  const auto* map = dynamic_cast<const GridLocalMap*>(atlas->Graph().Frame(0).map.get());
  ASSERT_NE(map, nullptr);
  EXPECT_EQ(map->Complexity(), 2);
  EXPECT_TRUE(map->LastUpdateMatched()) << ToString(map->LastAlignment().outcome);
  s.sensors = RangeSensors::kSonar;
  s.sonar_ring = FakeSonarRing24();
  EXPECT_NE(ValidateMapperSettings(s), "");
}

}  // namespace
}  // namespace atlas
