#include "core/sonar/sonar_geometry.h"

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "core/localmap/line_model.h"
#include "core/testing/degrees.h"

namespace atlas {
namespace {

// d range / d(robot, line) of PredictSonarRange against central differences.
void ExpectJacobiansMatchNumerical(const Pose2& robot, const SonarTransducer& t, const Vec2& line,
                                   double edge, double tol) {
  const SonarRangePrediction p = PredictSonarRange(robot, t, line(0), line(1), edge);
  const double eps = 1e-6;
  for (int i = 0; i < 3; ++i) {
    Vec3 a = robot.ToVector(), b = a;
    a(i) += eps;
    b(i) -= eps;
    const double num =
        (PredictSonarRange(Pose2{a(0), a(1), a(2)}, t, line(0), line(1), edge).range -
         PredictSonarRange(Pose2{b(0), b(1), b(2)}, t, line(0), line(1), edge).range) /
        (2 * eps);
    EXPECT_NEAR(p.d_pose(i), num, tol) << "pose " << i;
  }
  for (int i = 0; i < 2; ++i) {
    Vec2 a = line, b = line;
    a(i) += eps;
    b(i) -= eps;
    const double num = (PredictSonarRange(robot, t, a(0), a(1), edge).range -
                        PredictSonarRange(robot, t, b(0), b(1), edge).range) /
                       (2 * eps);
    EXPECT_NEAR(p.d_line(i), num, tol) << "line " << i;
  }
}

TEST(TangentLine, DistanceFromTransducerEqualsRange) {
  const Pose2 sensor{1.0, 2.0, 0.3};
  for (double phi : {-12 * kDeg, 0.0, 9 * kDeg}) {
    const Vec2 l = TangentLine(sensor, 2.5, phi);
    EXPECT_GE(l(0), 0.0);
    const double d = std::abs(l(0) - sensor.x * std::cos(l(1)) - sensor.y * std::sin(l(1)));
    EXPECT_NEAR(d, 2.5, 1e-12);
    // Normal from the transducer to the line at heading + phi.
    SonarTransducer t;
    t.pose = sensor;
    const SonarRangePrediction p = PredictSonarRange(Pose2{}, t, l(0), l(1));
    EXPECT_NEAR(p.range, 2.5, 1e-12);
    EXPECT_NEAR(p.incidence, phi, 1e-12);
    EXPECT_TRUE(p.in_cone);
  }
}

TEST(PredictSonarRange, WallAheadAndOutsideCone) {
  SonarTransducer t;  // at the robot centre, facing +x, 25 degree cone
  const Pose2 robot{0.5, 0.0, 0.0};
  // Wall x = 3: normal (1, 0), rho 3.
  SonarRangePrediction p = PredictSonarRange(robot, t, 3.0, 0.0);
  EXPECT_NEAR(p.range, 2.5, 1e-12);
  EXPECT_TRUE(p.in_cone);
  EXPECT_NEAR(p.foot.x(), 3.0, 1e-12);
  // Turned 20 degrees: outside the 12.5 degree half cone.
  p = PredictSonarRange(Pose2{0.5, 0.0, 20 * kDeg}, t, 3.0, 0.0);
  EXPECT_FALSE(p.in_cone);
  // Wall behind the transducer (x = -1): normal points backwards.
  p = PredictSonarRange(robot, t, 1.0, std::numbers::pi);
  EXPECT_NEAR(p.range, 1.5, 1e-12);
  EXPECT_FALSE(p.in_cone);
}

TEST(PredictSonarRange, JacobiansMatchNumerical) {
  SonarTransducer t;
  t.pose = Pose2{0.2, -0.13, 0.4};
  const Pose2 robot{1.1, -0.7, 0.25};
  for (const Vec2& line : {Vec2(4.0, 0.6), Vec2(0.5, -2.5), Vec2(3.0, 2.9)}) {
    ExpectJacobiansMatchNumerical(robot, t, line, 0.0, 1e-7);
  }
}

TEST(PredictSonarRange, EdgeEchoAlongTheConeEdgeRay) {
  SonarTransducer t;  // facing +x, half cone 12.5 degrees
  // Wall x = 3 seen from (0.5, 0) turned 20 degrees: the normal is 7.5 degrees outside the cone;
  // the edge ray (at 7.5 degrees from the normal) echoes at 2.5 / cos(7.5 deg).
  const Pose2 robot{0.5, 0.0, 20 * kDeg};
  SonarRangePrediction p = PredictSonarRange(robot, t, 3.0, 0.0, 0.3);
  EXPECT_FALSE(p.in_cone);
  EXPECT_TRUE(p.edge_echo);
  EXPECT_TRUE(p.echoes());
  const double psi = 20 * kDeg - 0.5 * t.beam_width;  // 7.5 degrees
  EXPECT_NEAR(p.range, 2.5 / std::cos(psi), 1e-12);
  EXPECT_NEAR(p.foot.x(), 3.0, 1e-12);
  EXPECT_NEAR(p.foot.y(), 2.5 * std::tan(psi), 1e-12);
  // Beyond the critical incidence (0.1 rad): no echo; without edge_incidence: none either.
  EXPECT_FALSE(PredictSonarRange(robot, t, 3.0, 0.0, 0.1).echoes());
  EXPECT_FALSE(PredictSonarRange(robot, t, 3.0, 0.0).echoes());
  // Jacobians of the edge range (both sides of the cone).
  t.pose = Pose2{0.2, -0.13, 0.4};
  for (const double heading : {0.0, 0.75}) {
    const Pose2 r{1.1, -0.7, heading};
    const Vec2 line(4.0, 0.6 + 0.3);
    ASSERT_TRUE(PredictSonarRange(r, t, line(0), line(1), 0.5).edge_echo) << heading;
    ExpectJacobiansMatchNumerical(r, t, line, 0.5, 1e-6);
  }
}

TEST(CommonTangentLines, RecoversWallFromTwoVantagePoints) {
  // Wall y = 2 (rho 2, alpha pi/2); two transducers facing up from different places.
  const Pose2 s1{0.0, 0.0, 95 * kDeg}, s2{1.5, 0.4, 85 * kDeg};
  Vec2 out[2];
  const double h = 12.5 * kDeg;
  const int n = CommonTangentLines(s1, 2.0, h, s2, 1.6, h, out);
  ASSERT_GE(n, 1);
  bool found = false;
  for (int i = 0; i < n; ++i) {
    found = found || (std::abs(out[i](0) - 2.0) < 1e-9 &&
                      std::abs(WrapAngle(out[i](1) - std::numbers::pi / 2)) < 1e-9);
  }
  EXPECT_TRUE(found);
  // Each solution is tangent to both arcs.
  for (int i = 0; i < n; ++i) {
    for (const auto& [s, r] : {std::pair{s1, 2.0}, std::pair{s2, 1.6}}) {
      EXPECT_NEAR(std::abs(out[i](0) - s.x * std::cos(out[i](1)) - s.y * std::sin(out[i](1))), r,
                  1e-9);
    }
  }
  // Arcs that no common tangent inside the cones touches.
  EXPECT_EQ(CommonTangentLines(s1, 2.0, h, Pose2{1.5, 0.4, -85 * kDeg}, 1.6, h, out), 0);
  EXPECT_EQ(CommonTangentLines(s1, 0.5, h, Pose2{3.0, 0.0, 90 * kDeg}, 4.0, h, out), 0);
}

TEST(ConeFootprint, EdgeRaysBoundThePartOfTheLineInTheCone) {
  const double half = 12.5 * std::numbers::pi / 180.0;
  double lo = 0.0, hi = 0.0;
  // Facing the line x = 2 head-on: +-2 tan(h) about the foot (positions along the line are y).
  ASSERT_TRUE(ConeFootprint(Pose2{0.0, 0.0, 0.0}, half, 2.0, 0.0, lo, hi));
  EXPECT_NEAR(lo, -2.0 * std::tan(half), 1e-12);
  EXPECT_NEAR(hi, 2.0 * std::tan(half), 1e-12);
  // Along the line: one edge ray crosses far ahead, the other never does.
  ASSERT_TRUE(ConeFootprint(Pose2{0.0, 0.0, std::numbers::pi / 2}, half, 2.0, 0.0, lo, hi));
  EXPECT_NEAR(lo, 2.0 * std::tan(std::numbers::pi / 2 - half), 1e-9);
  EXPECT_TRUE(std::isinf(hi) && hi > 0.0);
  // Facing away: no ray meets the line; lo, hi unchanged.
  lo = hi = 7.0;
  EXPECT_FALSE(ConeFootprint(Pose2{0.0, 0.0, std::numbers::pi}, half, 2.0, 0.0, lo, hi));
  EXPECT_EQ(lo, 7.0);
  // The same line given as (-2, pi): the same part of it, positions with the opposite sign.
  ASSERT_TRUE(ConeFootprint(Pose2{0.0, 0.0, 0.0}, half, -2.0, std::numbers::pi, lo, hi));
  EXPECT_NEAR(lo, -2.0 * std::tan(half), 1e-12);
  EXPECT_NEAR(hi, 2.0 * std::tan(half), 1e-12);
}

}  // namespace
}  // namespace atlas
