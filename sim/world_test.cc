#include "sim/world.h"

#include <gtest/gtest.h>

#include <sstream>

#include "sim/building_generator.h"

namespace atlas::sim {
namespace {

WorldParseResult Parse(const std::string& text) {
  std::istringstream in(text);
  return ParseWorld(in, "test.world");
}

TEST(World, GeneratedWorldRoundTripsExactly) {
  BuildingOptions o;
  o.min_rooms = 30;
  const World w = GenerateBuilding(o, 11);
  std::ostringstream out;
  WriteWorld(out, w);
  const WorldParseResult r = Parse(out.str());
  ASSERT_TRUE(r.ok()) << r.error;
  ASSERT_EQ(r.world.walls.size(), w.walls.size());
  ASSERT_EQ(r.world.nodes.size(), w.nodes.size());
  ASSERT_EQ(r.world.edges.size(), w.edges.size());
  for (size_t i = 0; i < w.walls.size(); ++i) {
    EXPECT_EQ(r.world.walls[i].a, w.walls[i].a);  // bit-exact: shortest round-trip printing
    EXPECT_EQ(r.world.walls[i].b, w.walls[i].b);
  }
  for (size_t i = 0; i < w.nodes.size(); ++i) {
    EXPECT_EQ(r.world.nodes[i].position, w.nodes[i].position);
    EXPECT_EQ(r.world.nodes[i].kind, w.nodes[i].kind);
  }
  for (size_t i = 0; i < w.edges.size(); ++i) {
    EXPECT_EQ(r.world.edges[i].from, w.edges[i].from);
    EXPECT_EQ(r.world.edges[i].to, w.edges[i].to);
  }
}

TEST(World, ParsesCommentsBlankLinesAndKinds) {
  const WorldParseResult r = Parse(
      "# a room\n\natlas-world 1\nwall 0 0 4 0  # floor\nwall 4 0 4 3\r\n"
      "node 0 1 1 corridor\nnode 1 2 1.5 door\nnode 2 3 2 room\nedge 0 1\nedge 1 2\n");
  ASSERT_TRUE(r.ok()) << r.error;
  EXPECT_EQ(r.world.walls.size(), 2u);
  EXPECT_EQ(r.world.walls[1].b, Vec2(4, 3));
  EXPECT_EQ(r.world.CountNodes(NodeKind::kDoor), 1);
  EXPECT_EQ(r.world.CountNodes(NodeKind::kRoom), 1);
  EXPECT_EQ(r.world.edges[1].to, 2);
}

TEST(World, ErrorsNameTheLineAndTheProblem) {
  struct Case {
    std::string text;
    std::string expect;
  };
  const Case cases[] = {
      {"", "test.world:0: empty input"},
      {"wall 0 0 1 1\n", "test.world:1: expected the header"},
      {"atlas-world 2\n", "test.world:1: expected the header"},
      {"atlas-world 1\nwall 0 0 1\n", "test.world:2: 'wall' needs 4 numbers"},
      {"atlas-world 1\nwall 0 0 1 x\n", "test.world:2: 'wall': 'x' is not a finite number"},
      {"atlas-world 1\nwall 0 0 1 nan\n", "is not a finite number"},
      {"atlas-world 1\nnode 1 0 0 room\n", "test.world:2: 'node': expected id 0"},
      {"atlas-world 1\nnode 0 0 0 kitchen\n", "kind must be corridor, door or room"},
      {"atlas-world 1\nnode 0 0 0 room\nedge 0 1\n", "test.world:3: 'edge': node ids"},
      {"atlas-world 1\n\nwindow 0 0\n", "test.world:3: unknown keyword 'window'"},
      {"atlas-world 1\nwall 0 0 1 1 mirror\n", "test.world:2: 'wall' needs 4 numbers"},
      {"atlas-world 1\nperson 0 0 1 1\n", "test.world:2: 'person' needs 5 numbers"},
      {"atlas-world 1\nperson 0 0 1 1 -1\n", "'person': speed must be in (0, 5]"},
  };
  for (const Case& c : cases) {
    const WorldParseResult r = Parse(c.text);
    EXPECT_FALSE(r.ok()) << c.text;
    EXPECT_NE(r.error.find(c.expect), std::string::npos) << r.error << " / want " << c.expect;
    EXPECT_TRUE(r.world.walls.empty());
  }
}

TEST(World, GlassWallsAndPeopleRoundTrip) {
  const WorldParseResult r =
      Parse("atlas-world 1\nwall 0 0 4 0 glass\nwall 4 0 4 3\nperson 1 1 3.5 1 1.25\n");
  ASSERT_TRUE(r.ok()) << r.error;
  ASSERT_EQ(r.world.walls.size(), 2u);
  EXPECT_TRUE(r.world.walls[0].glass);
  EXPECT_FALSE(r.world.walls[1].glass);
  ASSERT_EQ(r.world.people.size(), 1u);
  EXPECT_EQ(r.world.people[0].b, Vec2(3.5, 1));
  EXPECT_EQ(r.world.people[0].speed, 1.25);
  std::ostringstream out;
  WriteWorld(out, r.world);
  EXPECT_NE(out.str().find("wall 0 0 4 0 glass\nwall 4 0 4 3\n"), std::string::npos);
  EXPECT_NE(out.str().find("person 1 1 3.5 1 1.25\n"), std::string::npos);
}

TEST(World, PersonWalksToAndFro) {
  const Person p{Vec2(0, 0), Vec2(4, 0), 2.0};
  auto middle = [&](double t) {
    const auto legs = PersonLegs(p, t);
    return Vec2(0.5 * (legs[0].centre + legs[1].centre));
  };
  EXPECT_NEAR((middle(0.0) - Vec2(0, 0)).norm(), 0.0, 1e-12);
  EXPECT_NEAR((middle(1.0) - Vec2(2, 0)).norm(), 0.0, 1e-12);
  EXPECT_NEAR((middle(3.0) - Vec2(2, 0)).norm(), 0.0, 1e-12);  // on the way back
  EXPECT_NEAR((middle(4.0) - Vec2(0, 0)).norm(), 0.0, 1e-12);
  const auto legs = PersonLegs(p, 0.3);
  EXPECT_NEAR((legs[0].centre - legs[1].centre).y(), 0.2, 1e-12);  // across the path
  EXPECT_EQ(legs[0].radius, 0.06);
}

TEST(World, BoundsCoverWallsAndNodes) {
  World w;
  w.walls.push_back({Vec2(-1, 2), Vec2(3, 2)});
  w.nodes.push_back({Vec2(0, -5), NodeKind::kRoom});
  const Bounds b = WorldBounds(w);
  EXPECT_EQ(b.min, Vec2(-1, -5));
  EXPECT_EQ(b.max, Vec2(3, 2));
}

}  // namespace
}  // namespace atlas::sim
