#include "sim/simulation.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <sstream>

#include "sim/building_generator.h"

namespace atlas::sim {
namespace {

// Records everything, with a running hash of the values.
struct RecordingSink : SimulationSink {
  std::vector<TruthSample> truth;
  std::vector<OdometrySample> odometry;
  std::vector<LaserScan> scans;
  std::vector<SonarReading> sonar;
  std::vector<Time> stamps;  // every event, in arrival order
  double hash = 0.0;
  void OnTruth(const TruthSample& t) override {
    truth.push_back(t);
    stamps.push_back(t.stamp);
  }
  void OnOdometry(const OdometrySample& o, double, double) override {
    odometry.push_back(o);
    stamps.push_back(o.stamp);
    hash = hash * 0.999 + o.pose.x + 3 * o.pose.y + 7 * o.pose.theta;
  }
  void OnLaser(const LaserScan& s, const Pose2&) override {
    scans.push_back(s);
    stamps.push_back(s.stamp);
    for (float r : s.ranges) hash = hash * 0.999 + (IsReturn(r) ? r : -1.0);
  }
  void OnSonar(const SonarReading& r, const Pose2&) override {
    sonar.push_back(r);
    stamps.push_back(r.stamp);
    for (const SonarReturn& s : r.returns) hash = hash * 0.999 + (IsReturn(s.range) ? s.range : -1);
  }
};

World SmallBuilding() {
  BuildingOptions o;
  o.min_rooms = 20;
  return GenerateBuilding(o, 2);
}

SimulationOptions ShortRun(uint64_t seed) {
  SimulationOptions o;
  o.length_m = 50.0;
  o.sonar = true;
  o.laser_options.rate_hz = 37.5;  // not a divisor of the odometry rate
  o.seed = seed;
  return o;
}

TEST(Simulation, ReproducibleFromSeed) {
  const World w = SmallBuilding();
  RecordingSink a, b, c;
  Simulate(w, ShortRun(5), a);
  Simulate(w, ShortRun(5), b);
  Simulate(w, ShortRun(6), c);
  EXPECT_EQ(a.hash, b.hash);
  EXPECT_EQ(a.scans.size(), b.scans.size());
  EXPECT_NE(a.hash, c.hash);
}

TEST(Simulation, RatesOrderAndLength) {
  const World w = SmallBuilding();
  RecordingSink s;
  const SimulationSummary sum = Simulate(w, ShortRun(1), s);
  ASSERT_EQ(sum.error, "");
  EXPECT_GE(sum.distance_m, 50.0);
  EXPECT_LT(sum.distance_m, 51.0);
  for (size_t i = 1; i < s.stamps.size(); ++i) ASSERT_LE(s.stamps[i - 1], s.stamps[i]) << i;
  const double duration = ToSeconds(s.truth.back().stamp - s.truth.front().stamp);
  EXPECT_NEAR(duration, sum.duration_s, 1e-6);
  EXPECT_NEAR(s.truth.size(), duration * 50.0 + 1, 1.0);
  EXPECT_NEAR(s.scans.size(), duration * 37.5, 1.0);
  EXPECT_NEAR(s.sonar.size(), duration * 10.0, 1.0);
  EXPECT_EQ(s.truth.size(), s.odometry.size());
  // Truth distance agrees with the summary; odometry starts at the truth and drifts a little.
  double d = 0.0;
  for (size_t i = 1; i < s.truth.size(); ++i)
    d += std::hypot(s.truth[i].pose.x - s.truth[i - 1].pose.x,
                    s.truth[i].pose.y - s.truth[i - 1].pose.y);
  EXPECT_NEAR(d, sum.distance_m, 0.01);
  EXPECT_EQ(s.odometry.front().pose.x, s.truth.front().pose.x);
  const double drift = std::hypot(s.odometry.back().pose.x - s.truth.back().pose.x,
                                  s.odometry.back().pose.y - s.truth.back().pose.y);
  EXPECT_GT(drift, 0.001);
  EXPECT_LT(drift, 20.0);
  // Laser scans see walls: most beams return inside a building.
  long returns = 0, beams = 0;
  for (const LaserScan& scan : s.scans)
    for (float r : scan.ranges) returns += IsReturn(r), ++beams;
  EXPECT_GT(returns, 0.9 * beams);
}

// A hand-written world: a square corridor 2 m wide round a 6 x 6 m block, driven round and
// round: the route comes back to its start (a loop closure).
TEST(Simulation, DrivesAWorldReadFromText) {
  std::istringstream text(R"(atlas-world 1
# outer and inner walls of a square ring corridor; centreline is the square (1,1)-(9,9)
wall 0 0 10 0
wall 10 0 10 10
wall 10 10 0 10
wall 0 10 0 0
wall 2 2 8 2
wall 8 2 8 8
wall 8 8 2 8
wall 2 8 2 2
node 0 1 1 corridor
node 1 9 1 corridor
node 2 9 9 corridor
node 3 1 9 corridor
edge 0 1
edge 1 2
edge 2 3
edge 3 0
)");
  const WorldParseResult parsed = ParseWorld(text, "ring");
  ASSERT_TRUE(parsed.ok()) << parsed.error;
  EXPECT_GE(StartNode(parsed.world), 0);
  RecordingSink s;
  SimulationOptions o = ShortRun(3);
  o.length_m = 70.0;  // more than two laps of 32 m
  const SimulationSummary sum = Simulate(parsed.world, o, s);
  ASSERT_EQ(sum.error, "");
  const Pose2 start = s.truth.front().pose;
  int returns_to_start = 0;
  bool away = false;
  for (const TruthSample& t : s.truth) {
    const double d = std::hypot(t.pose.x - start.x, t.pose.y - start.y);
    if (d > 5.0) away = true;
    if (away && d < 0.3) ++returns_to_start, away = false;
  }
  EXPECT_GE(returns_to_start, 2);
  // Every laser return lies on one of the eight walls (x or y in {0, 2, 8, 10}).
  for (const LaserScan& scan : s.scans) {
    for (size_t i = 0; i < scan.ranges.size(); i += 10) {
      if (!IsReturn(scan.ranges[i])) continue;
      const TruthSample& t = s.truth[static_cast<size_t>(
          std::lround(ToSeconds(scan.stamp - s.truth.front().stamp) * 50.0))];
      const double a = t.pose.theta + scan.angle_min + i * scan.angle_increment;
      const double x = t.pose.x + scan.ranges[i] * std::cos(a);
      const double y = t.pose.y + scan.ranges[i] * std::sin(a);
      double best = 1e9;
      for (double c : {0.0, 2.0, 8.0, 10.0})
        best = std::min({best, std::abs(x - c), std::abs(y - c)});
      ASSERT_LT(best, 0.1) << "return at " << x << " " << y;
    }
  }
}

TEST(Simulation, WorldWithoutRouteGraphIsAnError) {
  World w;
  w.walls.push_back({Vec2(0, 0), Vec2(1, 0)});
  RecordingSink s;
  const SimulationSummary sum = Simulate(w, ShortRun(1), s);
  EXPECT_NE(sum.error, "");
  EXPECT_TRUE(s.truth.empty());
}

}  // namespace
}  // namespace atlas::sim
