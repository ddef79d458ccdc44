#include "sim/building_generator.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <set>

#include "sim/ray_caster.h"

namespace atlas::sim {
namespace {

TEST(BuildingOptions, DefaultsValidBadRejected) {
  EXPECT_EQ(BuildingOptions{}.Validate(), "");
  BuildingOptions o;
  o.corridor_width = 0.5;
  EXPECT_NE(o.Validate(), "");
  o = {};
  o.door_width = 5.0;
  EXPECT_NE(o.Validate(), "");
  o = {};
  o.min_rooms = 0;
  EXPECT_NE(o.Validate(), "");
}

TEST(BuildingGenerator, HasAtLeastTheRoomsAskedFor) {
  for (int rooms : {1, 10, 24, 100, 150}) {
    BuildingOptions o;
    o.min_rooms = rooms;
    const World w = GenerateBuilding(o, 3);
    EXPECT_GE(w.CountNodes(NodeKind::kRoom), rooms);
    EXPECT_LE(w.CountNodes(NodeKind::kRoom), 2 * rooms + 20) << "grid grew too far";
    EXPECT_EQ(w.CountNodes(NodeKind::kDoor), w.CountNodes(NodeKind::kRoom));
  }
}

TEST(BuildingGenerator, SameSeedSameBuildingOtherSeedOther) {
  BuildingOptions o;
  o.min_rooms = 40;
  const World a = GenerateBuilding(o, 7), b = GenerateBuilding(o, 7), c = GenerateBuilding(o, 8);
  ASSERT_EQ(a.walls.size(), b.walls.size());
  for (size_t i = 0; i < a.walls.size(); ++i) ASSERT_EQ(a.walls[i].a, b.walls[i].a);
  bool differs = a.walls.size() != c.walls.size();
  for (size_t i = 0; !differs && i < a.walls.size(); ++i) differs = a.walls[i].a != c.walls[i].a;
  EXPECT_TRUE(differs);
}

TEST(BuildingGenerator, RouteGraphIsConnectedWithLoopsOfSeveralSizes) {
  BuildingOptions o;
  o.min_rooms = 100;
  const World w = GenerateBuilding(o, 1);
  const auto adj = RouteAdjacency(w);
  // Connected: every node reachable from node 0.
  EXPECT_EQ(CountReachableNodes(w, 0), static_cast<int>(w.nodes.size()));
  // Independent loops (cycle rank E - V + 1): one per block of the grid, at least 9 here.
  const int cycle_rank = static_cast<int>(w.edges.size()) - static_cast<int>(w.nodes.size()) + 1;
  EXPECT_GE(cycle_rank, 9);
  // Loops of several sizes: the corridor ring round each block has its own perimeter. Junctions
  // are the corridor nodes of degree >= 3 or corners of degree 2 with a turn; their x and y
  // values give the block sizes.
  std::set<long> xs, ys;
  for (size_t i = 0; i < w.nodes.size(); ++i)
    if (w.nodes[i].kind == NodeKind::kCorridor && adj[i].size() >= 2) {
      int vertical = 0;
      for (int m : adj[i])
        vertical += std::abs(w.nodes[m].position.x() - w.nodes[i].position.x()) < 1e-9;
      if (vertical > 0) {
        xs.insert(std::lround(w.nodes[i].position.x() * 100));
        ys.insert(std::lround(w.nodes[i].position.y() * 100));
      }
    }
  std::set<long> widths, heights;
  for (auto a = xs.begin(), b = std::next(xs.begin()); b != xs.end(); ++a, ++b)
    widths.insert(*b - *a);
  for (auto a = ys.begin(), b = std::next(ys.begin()); b != ys.end(); ++a, ++b)
    heights.insert(*b - *a);
  EXPECT_GE(widths.size(), 3u);
  EXPECT_GE(heights.size(), 2u);
  EXPECT_GE(widths.size() * heights.size(), 6u) << "block loops should differ in size";
}

TEST(BuildingGenerator, EveryRouteEdgeIsFreeForARobotOfHalfWidth25cm) {
  BuildingOptions o;
  o.min_rooms = 100;
  for (uint64_t seed : {1, 2, 3}) {
    const World w = GenerateBuilding(o, seed);
    const RayCaster c(w.walls, 1.0);
    for (const RouteEdge& e : w.edges) {
      const Vec2 a = w.nodes[e.from].position, b = w.nodes[e.to].position;
      const Vec2 d = b - a;
      const double len = d.norm();
      const Vec2 n = Vec2(-d.y(), d.x()) / len;
      for (double off : {-0.25, 0.0, 0.25}) {
        const Vec2 s = a + off * n;
        const RayHit fwd = c.Cast(s, d, len);
        EXPECT_FALSE(fwd.hit()) << "seed " << seed << " edge " << e.from << "-" << e.to
                                << " offset " << off << " blocked at " << fwd.range;
      }
    }
  }
}

}  // namespace
}  // namespace atlas::sim
