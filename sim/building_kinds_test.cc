#include "sim/building_kinds.h"

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <set>
#include <sstream>

#include "sim/building_generator.h"
#include "sim/laser_model.h"
#include "sim/ray_caster.h"
#include "sim/route.h"
#include "sim/simulation.h"

namespace atlas::sim {
namespace {

constexpr double kPi = std::numbers::pi;

double PointToSegment(const Vec2& p, const Vec2& a, const Vec2& b) {
  const Vec2 d = b - a;
  const double t = std::clamp((p - a).dot(d) / std::max(d.squaredNorm(), 1e-18), 0.0, 1.0);
  return (p - (a + t * d)).norm();
}

double SegmentToSegment(const Vec2& p, const Vec2& q, const Vec2& a, const Vec2& b) {
  auto cross = [](const Vec2& u, const Vec2& v) { return u.x() * v.y() - u.y() * v.x(); };
  if (((cross(q - p, a - p) > 0) != (cross(q - p, b - p) > 0)) &&
      ((cross(b - a, p - a) > 0) != (cross(b - a, q - a) > 0)))
    return 0.0;
  return std::min({PointToSegment(p, a, b), PointToSegment(q, a, b), PointToSegment(a, p, q),
                   PointToSegment(b, p, q)});
}

// Every wall as opaque, for the geometric checks.
RayCaster OpaqueCaster(const World& world) {
  std::vector<Wall> walls = world.walls;
  for (Wall& w : walls) w.glass = false;
  return RayCaster(walls);
}

class EveryKind : public ::testing::TestWithParam<BuildingKind> {};

TEST_P(EveryKind, ValidWorldForSeveralSeeds) {
  const BuildingKind kind = GetParam();
  for (uint64_t seed : {1, 2, 3}) {
    SCOPED_TRACE(std::string(ToString(kind)) + " seed " + std::to_string(seed));
    const World world = GenerateKind(kind, seed);
    ASSERT_GT(world.walls.size(), 4u);
    ASSERT_GE(StartNode(world), 0);
    // The route graph is connected and every edge keeps 0.3 m from every wall.
    EXPECT_EQ(CountReachableNodes(world, 0), static_cast<int>(world.nodes.size()));
    for (const RouteEdge& e : world.edges) {
      const Vec2 &a = world.nodes[e.from].position, &b = world.nodes[e.to].position;
      for (const Wall& w : world.walls)
        ASSERT_GE(SegmentToSegment(a, b, w.a, w.b), 0.3)
            << "edge " << e.from << "-" << e.to << " runs into a wall";
    }
    // Closed: from every node, a ray in every direction meets a wall (glass included).
    const RayCaster caster = OpaqueCaster(world);
    int escaping = 0;
    for (const RouteNode& n : world.nodes)
      for (int k = 0; k < 72; ++k) {
        const double angle = (k + 0.37) * kPi / 36;  // off the axes: no grazing rays
        const Vec2 dir(std::cos(angle), std::sin(angle));
        escaping += !caster.Cast(n.position, dir, 1e4).hit();
      }
    if (KindIsClosed(kind)) {
      EXPECT_EQ(escaping, 0);
    } else {
      EXPECT_GT(escaping, 0);
    }
    // The route comes back to where it has been: some node is met again after 30 m.
    const std::vector<int> route = PlanRoute(world, 1500.0, StartNode(world), seed);
    double travelled = 0.0;
    std::vector<double> at(route.size(), 0.0);
    bool returns = false;
    for (size_t i = 1; i < route.size(); ++i) {
      travelled += (world.nodes[route[i]].position - world.nodes[route[i - 1]].position).norm();
      at[i] = travelled;
      for (size_t j = 0; j < i && !returns; ++j)
        returns = route[j] == route[i] && at[i] - at[j] > 30.0;
    }
    EXPECT_TRUE(returns);
  }
}

TEST_P(EveryKind, SameSeedSameWorldAndTextRoundTrip) {
  const World a = GenerateKind(GetParam(), 5), b = GenerateKind(GetParam(), 5);
  std::ostringstream ta, tb;
  WriteWorld(ta, a);
  WriteWorld(tb, b);
  EXPECT_EQ(ta.str(), tb.str());
  std::istringstream in(ta.str());
  const WorldParseResult r = ParseWorld(in, "kind");
  ASSERT_TRUE(r.ok()) << r.error;
  std::ostringstream again;
  WriteWorld(again, r.world);
  EXPECT_EQ(again.str(), ta.str());
  ASSERT_EQ(r.world.walls.size(), a.walls.size());
  for (size_t i = 0; i < a.walls.size(); ++i) EXPECT_EQ(r.world.walls[i].glass, a.walls[i].glass);
  EXPECT_EQ(r.world.people.size(), a.people.size());
}

INSTANTIATE_TEST_SUITE_P(Kinds, EveryKind, ::testing::ValuesIn(AllBuildingKinds()),
                         [](const auto& info) { return std::string(ToString(info.param)); });

TEST(BuildingKinds, NamesParseBack) {
  for (BuildingKind k : AllBuildingKinds()) {
    BuildingKind parsed = BuildingKind::kOffice;
    ASSERT_TRUE(ParseBuildingKind(ToString(k), &parsed));
    EXPECT_EQ(parsed, k);
  }
  BuildingKind k;
  EXPECT_FALSE(ParseBuildingKind("castle", &k));
}

// The default office is the generator's, byte for byte: the FNV-1a hash of seed 1's world
// text as atlas-sim wrote it before the kinds existed.
TEST(BuildingKinds, OfficeIsTheDefaultGeneratorUnchanged) {
  std::ostringstream text;
  WriteWorld(text, GenerateKind(BuildingKind::kOffice, 1));
  uint64_t h = 0xcbf29ce484222325ULL;
  for (unsigned char c : text.str()) h = (h ^ c) * 0x100000001b3ULL;
  EXPECT_EQ(h, 0xca512cfc8e91d171ULL);
}

TEST(BuildingKinds, GlassGivesNoReturn) {
  const World glass = GenerateKind(BuildingKind::kGlass, 1);
  int panes = 0;
  for (const Wall& w : glass.walls) panes += w.glass;
  EXPECT_GT(panes, 10);
  // A pane in front of a wall: the ray passes the pane and meets the wall behind it.
  const std::vector<Wall> walls{Wall{Vec2(2, -1), Vec2(2, 1), true}, Wall{Vec2(5, -1), Vec2(5, 1)}};
  const RayCaster caster(walls);
  EXPECT_NEAR(caster.Cast(Vec2::Zero(), Vec2(1, 0), 30).range, 5.0, 1e-12);
  EXPECT_NEAR(caster.CastBruteForce(Vec2::Zero(), Vec2(1, 0), 30).range, 5.0, 1e-12);
  const RayCaster pane_only({walls[0]});
  EXPECT_FALSE(pane_only.Cast(Vec2::Zero(), Vec2(1, 0), 30).hit());
}

TEST(BuildingKinds, PeopleMoveAndTheLaserSeesThem) {
  const World world = GenerateKind(BuildingKind::kPeople, 2);
  ASSERT_GE(world.people.size(), 3u);
  const Person& p = world.people.front();
  const auto legs0 = PersonLegs(p, 0.0), legs1 = PersonLegs(p, 2.0);
  const Vec2 mid0 = 0.5 * (legs0[0].centre + legs0[1].centre);
  const Vec2 mid1 = 0.5 * (legs1[0].centre + legs1[1].centre);
  EXPECT_NEAR((mid1 - mid0).norm(), std::min(2.0 * p.speed, (p.b - p.a).norm()), 1e-9);
  // Seen from 3 m behind the start, along the path, the legs are the nearest return; without
  // them the corridor goes on.
  const Vec2 u = (p.b - p.a).normalized();
  const Vec2 eye = p.a - 3.0 * u;
  LaserOptions lo;
  lo.range_sigma = 0.0;
  lo.dropout_probability = 0.0;
  const RayCaster caster(world.walls);
  const Pose2 robot{eye.x(), eye.y(), std::atan2(u.y(), u.x())};
  const std::vector<Disc> obstacles(legs0.begin(), legs0.end());
  const LaserScan with = LaserModel(lo, 1).Scan(caster, robot, Time{}, obstacles);
  const LaserScan without = LaserModel(lo, 1).Scan(caster, robot, Time{});
  int nearer = 0;
  for (size_t i = 0; i < with.ranges.size(); ++i)
    if (with.ranges[i] < (without.ranges[i] == kNoReturn ? 1e9 : without.ranges[i]) - 0.5) {
      EXPECT_NEAR(with.ranges[i], 3.0, 0.25);
      ++nearer;
    }
  EXPECT_GE(nearer, 2);
  for (const Person& q : world.people) {
    for (const Wall& w : world.walls) EXPECT_GE(PointToSegment(q.a, w.a, w.b), 0.3);
  }
}

TEST(BuildingKinds, CampusReturnsBeyondThirtyMetresAndHallWiderThanTheLaser) {
  for (uint64_t seed : {1, 2}) {
    const World campus = GenerateKind(BuildingKind::kCampus, seed);
    const RayCaster c(campus.walls);
    int far = 0;
    for (const RouteNode& n : campus.nodes)
      for (int k = 0; k < 360; ++k) {
        const RayHit hit =
            c.Cast(n.position, Vec2(std::cos(k * kPi / 180), std::sin(k * kPi / 180)),
                   KindLaserMaxRange(BuildingKind::kCampus));
        far += hit.hit() && hit.range > 30.0;
      }
    EXPECT_GT(far, 500) << "seed " << seed;
    const World hall = GenerateKind(BuildingKind::kHall, seed);
    const RayCaster h(hall.walls);
    const Vec2 middle = hall.nodes[StartNode(hall)].position;
    int unseen = 0;
    for (int k = 0; k < 360; ++k)
      unseen += !h.Cast(middle, Vec2(std::cos(k * kPi / 180), std::sin(k * kPi / 180)),
                        KindLaserMaxRange(BuildingKind::kHall))
                     .hit();
    EXPECT_GT(unseen, 90) << "seed " << seed;
  }
}

TEST(BuildingKinds, CorridorRepeatsAtAFixedPitch) {
  const World world = GenerateKind(BuildingKind::kCorridor, 4);
  std::vector<double> doors;
  for (const RouteNode& n : world.nodes)
    if (n.kind == NodeKind::kDoor && n.position.y() < 3.0) doors.push_back(n.position.x());
  ASSERT_GE(doors.size(), 6u);
  std::sort(doors.begin(), doors.end());
  std::set<long> gaps;
  for (size_t i = 1; i < doors.size(); ++i)
    gaps.insert(std::lround(1000.0 * (doors[i] - doors[i - 1])));
  EXPECT_LE(gaps.size(), 2u);  // one pitch, and twice it across the cross corridor
}

}  // namespace
}  // namespace atlas::sim
