#include "sim/route.h"

#include <gtest/gtest.h>

#include <cmath>
#include <map>
#include <numbers>
#include <set>

#include "sim/building_generator.h"
#include "sim/ray_caster.h"

namespace atlas::sim {
namespace {

World Building() {
  BuildingOptions o;
  o.min_rooms = 40;
  return GenerateBuilding(o, 4);
}

TEST(PlanRoute, FollowsEdgesIsLongEnoughAndRevisitsPlaces) {
  const World w = Building();
  std::set<std::pair<int, int>> edges;
  for (const RouteEdge& e : w.edges) edges.insert({std::min(e.from, e.to), std::max(e.from, e.to)});
  const std::vector<int> r = PlanRoute(w, 2000.0, 0, 5);
  ASSERT_GE(r.size(), 2u);
  double length = 0.0;
  std::map<int, int> visits;
  for (size_t i = 0; i + 1 < r.size(); ++i) {
    ASSERT_TRUE(edges.count({std::min(r[i], r[i + 1]), std::max(r[i], r[i + 1])}))
        << "step " << i << " is not an edge";
    length += (w.nodes[r[i + 1]].position - w.nodes[r[i]].position).norm();
  }
  for (int n : r) ++visits[n];
  EXPECT_GE(length, 2000.0);
  // Loop closures: junctions are passed again and again; rooms are entered.
  int junctions_revisited = 0;
  for (const auto& [n, k] : visits)
    junctions_revisited += w.nodes[n].kind == NodeKind::kCorridor && k >= 3;
  EXPECT_GE(junctions_revisited, 20);
  std::set<int> rooms;
  for (int n : r)
    if (w.nodes[n].kind == NodeKind::kRoom) rooms.insert(n);
  EXPECT_GE(rooms.size(), 10u);
  // Same seed, same route.
  EXPECT_EQ(PlanRoute(w, 2000.0, 0, 5), r);
  EXPECT_NE(PlanRoute(w, 2000.0, 0, 6), r);
}

TEST(DiffDriveFollower, RespectsLimitsReachesTheEndAndNeverCrossesAWall) {
  const World w = Building();
  const RayCaster caster(w.walls, 1.0);
  std::vector<Vec2> waypoints;
  for (int id : PlanRoute(w, 400.0, 0, 2)) waypoints.push_back(w.nodes[id].position);
  MotionOptions o;
  DiffDriveFollower robot(o, waypoints);
  const double dt = 0.02;
  Pose2 prev = robot.pose();
  double prev_v = 0.0;
  int steps = 0;
  while (robot.Step(dt)) {
    ASSERT_LT(++steps, 200000) << "the robot got stuck";
    EXPECT_LE(std::abs(robot.speed()), o.max_speed + 1e-9);
    EXPECT_LE(std::abs(robot.turn_rate()), o.max_turn_rate + 1e-9);
    EXPECT_LE(std::abs(robot.speed() - prev_v), o.max_accel * dt + 1e-9);
    const Pose2 p = robot.pose();
    const Vec2 step(p.x - prev.x, p.y - prev.y);
    if (step.norm() > 1e-9) {
      ASSERT_FALSE(caster.Cast(Vec2(prev.x, prev.y), step, step.norm()).hit())
          << "crossed a wall at " << p.x << " " << p.y;
    }
    // Clearance: no wall within 0.2 m of the robot's centre.
    for (int k = 0; k < 8; ++k) {
      const double a = k * std::numbers::pi / 4;
      ASSERT_FALSE(caster.Cast(Vec2(p.x, p.y), Vec2(std::cos(a), std::sin(a)), 0.2).hit())
          << "touches a wall at " << p.x << " " << p.y;
    }
    prev = p;
    prev_v = robot.speed();
  }
  EXPECT_NEAR(robot.pose().x, waypoints.back().x(), 0.1);
  EXPECT_NEAR(robot.pose().y, waypoints.back().y(), 0.1);
  EXPECT_GT(robot.distance(), 380.0);
  // It drives at a useful speed on average (turning in place counts against it).
  EXPECT_GT(robot.distance() / (steps * dt), 0.4);
}

}  // namespace
}  // namespace atlas::sim
