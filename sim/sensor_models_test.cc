#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "core/testing/degrees.h"
#include "sim/fast_noise.h"
#include "sim/laser_model.h"
#include "sim/sonar_model.h"

namespace atlas::sim {
namespace {

TEST(FastNoise, QuantileAndMoments) {
  FastNoise n(1);
  double s = 0, s2 = 0, u = 0;
  const int k = 200000;
  for (int i = 0; i < k; ++i) {
    const double x = n.Normal();
    s += x;
    s2 += x * x;
    u += n.Uniform();
  }
  EXPECT_NEAR(s / k, 0.0, 0.01);
  EXPECT_NEAR(s2 / k, 1.0, 0.01);
  EXPECT_NEAR(u / k, 0.5, 0.005);
  int hits = 0;
  for (int i = 0; i < k; ++i) hits += n.Chance(0.1);
  EXPECT_NEAR(hits / double(k), 0.1, 0.003);
}

// A long wall along y = 5, and the robot at the origin facing +y.
std::vector<Wall> WallAhead() { return {{Vec2(-100, 5), Vec2(100, 5)}}; }

TEST(LaserModel, RangeNoiseHasTheConfiguredStatistics) {
  const RayCaster caster(WallAhead());
  LaserOptions o;
  o.beams = 361;
  o.range_sigma = 0.02;
  o.dropout_probability = 0.0;
  LaserModel laser(o, 3);
  const Pose2 robot{0, 0, std::numbers::pi / 2};
  double sum = 0, sum2 = 0;
  int n = 0;
  for (int s = 0; s < 200; ++s) {
    const LaserScan scan = laser.Scan(caster, robot, Time{});
    ASSERT_EQ(scan.ranges.size(), 361u);
    // Beams within 30 degrees of straight ahead: true range 5 / cos(bearing).
    for (int i = 120; i <= 240; ++i) {
      const double bearing = scan.angle_min + i * scan.angle_increment;
      const double err = scan.ranges[i] - 5.0 / std::cos(bearing);
      sum += err;
      sum2 += err * err;
      ++n;
    }
  }
  const double mean = sum / n, sd = std::sqrt(sum2 / n - mean * mean);
  EXPECT_NEAR(mean, 0.0, 0.001);
  EXPECT_NEAR(sd, 0.02, 0.001);
}

TEST(LaserModel, GeometryMaxRangeAndDropouts) {
  const RayCaster caster(WallAhead());
  LaserOptions o;
  o.beams = 181;
  o.max_range = 8.0;
  o.range_sigma = 0.0;
  o.dropout_probability = 0.0;
  LaserModel laser(o, 3);
  // Facing +x, the wall is to the left: beam 0 (-90 deg, right) sees nothing, beam 180
  // (+90 deg, left) sees it at 5 m; beams beyond 8 m have no return.
  const LaserScan scan = laser.Scan(caster, Pose2{0, 0, 0}, FromSeconds(2.0));
  EXPECT_EQ(scan.stamp, FromSeconds(2.0));
  EXPECT_NEAR(scan.angle_min, -std::numbers::pi / 2, 1e-6);
  EXPECT_NEAR(scan.angle_increment, kDeg, 1e-6);
  EXPECT_FALSE(IsReturn(scan.ranges[0]));
  EXPECT_NEAR(scan.ranges[180], 5.0, 1e-5);
  EXPECT_NEAR(scan.ranges[150], 5.0 / std::sin(60 * kDeg), 1e-5);
  EXPECT_FALSE(IsReturn(scan.ranges[120]));  // 30 deg: 10 m > max range
  // Dropouts at the configured rate.
  o.dropout_probability = 0.2;
  LaserModel dropping(o, 4);
  int lost = 0, total = 0;
  for (int s = 0; s < 100; ++s) {
    const LaserScan d = dropping.Scan(caster, Pose2{0, 0, 0}, Time{});
    for (int i = 160; i <= 180; ++i, ++total) lost += !IsReturn(d.ranges[i]);
  }
  EXPECT_NEAR(lost / double(total), 0.2, 0.03);
}

TEST(LaserModel, SameSeedSameScans) {
  const RayCaster caster(WallAhead());
  LaserModel a(LaserOptions{}, 9), b(LaserOptions{}, 9), c(LaserOptions{}, 10);
  const Pose2 p{0, 0, 1.0};
  const LaserScan sa = a.Scan(caster, p, Time{}), sb = b.Scan(caster, p, Time{}),
                  sc = c.Scan(caster, p, Time{});
  EXPECT_EQ(sa.ranges, sb.ranges);
  EXPECT_NE(sa.ranges, sc.ranges);
}

SonarOptions OneTransducer(double multipath) {
  SonarOptions o;
  o.ring = {SonarTransducer{}};  // at the robot's centre, facing forward, 25 deg, 5 m
  o.multipath_probability = multipath;
  o.range_sigma = 0.0;
  o.range_sigma_per_m = 0.0;
  return o;
}

TEST(SonarModel, RingsHaveTheirTransducers) {
  EXPECT_EQ(P3dxSonarRing().size(), 16u);
  EXPECT_EQ(B21SonarRing().size(), 24u);
  EXPECT_NEAR(P3dxSonarRing()[3].pose.theta, 10 * kDeg, 1e-9);
  EXPECT_EQ(SonarOptions{}.Validate(), "");
}

TEST(SonarModel, FirstReturnInsideTheConeNotAlongTheAxis) {
  // Facing a wall 2 m ahead at normal incidence: the range is the perpendicular distance.
  SonarModel sonar(OneTransducer(0.0), 1);
  const RayCaster wall({{Vec2(2, -10), Vec2(2, 10)}});
  EXPECT_NEAR(sonar.Fire(wall, Pose2{0, 0, 0}, 0), 2.0, 1e-6);
  // Turned 10 degrees (inside the 12.5 degree half-cone): still the perpendicular distance,
  // not 2 / cos(10 deg) along the axis, because the nearest echo in the cone comes back.
  EXPECT_NEAR(sonar.Fire(wall, Pose2{0, 0, 10 * kDeg}, 0),
              2.0 / std::cos(10 * kDeg - 12.5 * kDeg * 0.75), 0.02);
  EXPECT_LT(sonar.Fire(wall, Pose2{0, 0, 10 * kDeg}, 0), 2.0 / std::cos(10 * kDeg));
}

TEST(SonarModel, SpecularMissesHappenAtHighIncidence) {
  SonarModel sonar(OneTransducer(0.0), 1);
  const RayCaster wall({{Vec2(2, -50), Vec2(2, 50)}});
  int returns_low = 0, returns_high = 0;
  for (int deg = 0; deg <= 80; deg += 2) {
    const bool got = IsReturn(sonar.Fire(wall, Pose2{0, 0, deg * kDeg}, 0));
    if (deg <= 20) returns_low += got;
    if (deg >= 40) returns_high += got;
  }
  EXPECT_EQ(returns_low, 11);  // every angle up to 20 deg echoes
  EXPECT_EQ(returns_high, 0);  // none from 40 deg on: the sound is reflected away
}

TEST(SonarModel, MultipathGivesALongRangeAfterASecondBounce) {
  // A wall at x = 2 hit at 50 degrees incidence at (2, -2.38); the reflected sound goes
  // down-left to a wall at y = -4 and back: half path (3.11 + 2.12 + 4.05) / 2 = 4.64 m.
  SonarModel sonar(OneTransducer(1.0), 1);
  const RayCaster walls({{Vec2(2, -50), Vec2(2, 50)}, {Vec2(-50, -4), Vec2(50, -4)}});
  const Pose2 robot{0, 0, -50 * kDeg};
  const float r = sonar.Fire(walls, robot, 0);
  const double true_range = 2.0 / std::cos(50 * kDeg);
  ASSERT_TRUE(IsReturn(r));
  EXPECT_GT(r, true_range + 0.5);
  EXPECT_NEAR(r, 4.64, 0.02);
  // Without the second wall the sound is lost.
  SonarModel lost(OneTransducer(1.0), 1);
  const RayCaster one({{Vec2(2, -50), Vec2(2, 50)}});
  EXPECT_FALSE(IsReturn(lost.Fire(one, robot, 0)));
}

TEST(SonarModel, ReadingsCarryTheTransducersFiredSinceTheLast) {
  SonarOptions o;
  o.reading_hz = 10.0;
  o.firings_per_second = 40.0;
  SonarModel sonar(o, 1);
  const RayCaster walls({{Vec2(-3, -3), Vec2(3, -3)},
                         {Vec2(3, -3), Vec2(3, 3)},
                         {Vec2(3, 3), Vec2(-3, 3)},
                         {Vec2(-3, 3), Vec2(-3, -3)}});
  std::vector<int> fired;
  for (int k = 0; k < 8; ++k) {
    const SonarReading r = sonar.Read(walls, Pose2{}, FromSeconds(k * 0.1));
    EXPECT_EQ(r.returns.size(), 4u);
    for (const SonarReturn& s : r.returns) fired.push_back(s.transducer);
  }
  for (int i = 0; i < 32; ++i) EXPECT_EQ(fired[i], i % 16);
}

}  // namespace
}  // namespace atlas::sim
