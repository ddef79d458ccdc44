#include "core/localmap/line_model.h"

#include <gtest/gtest.h>

#include <numbers>

namespace atlas {
namespace {

constexpr double kEps = 1e-6;

// Central-difference Jacobian of f: R^N -> R^2 at v.
template <int N, typename F>
Eigen::Matrix<double, 2, N> Numerical(const F& f, const Eigen::Matrix<double, N, 1>& v) {
  Eigen::Matrix<double, 2, N> j;
  for (int i = 0; i < N; ++i) {
    Eigen::Matrix<double, N, 1> p = v, m = v;
    p(i) += kEps;
    m(i) -= kEps;
    j.col(i) = (f(p) - f(m)) / (2 * kEps);
  }
  return j;
}

Pose2 P(const Vec3& v) { return Pose2{v(0), v(1), v(2)}; }

TEST(LineModelTest, PredictLineJacobiansMatchNumerical) {
  const Pose2 robot{1.3, -0.7, 0.4};
  const double rho = 3.2, alpha = 2.1;
  const LinePrediction p = PredictLine(robot, rho, alpha);
  const auto by_pose = Numerical<3>([&](const Vec3& v) { return PredictLine(P(v), rho, alpha).z; },
                                    robot.ToVector());
  const auto by_line = Numerical<2>([&](const Vec2& l) { return PredictLine(robot, l(0), l(1)).z; },
                                    Vec2(rho, alpha));
  EXPECT_LT((by_pose - p.d_pose).norm(), 1e-7) << by_pose << "\n" << p.d_pose;
  EXPECT_LT((by_line - p.d_line).norm(), 1e-7) << by_line << "\n" << p.d_line;
}

TEST(LineModelTest, FlippedInnovationJacobiansMatchNumerical) {
  // The robot is beyond the line: the predicted rho is negative and must be flipped.
  const Pose2 robot{5.0, 1.0, -0.3};
  const double rho = 2.0, alpha = 0.2;
  LinePrediction p = PredictLine(robot, rho, alpha);
  ASSERT_LT(p.z(0), 0.0);
  Vec2 observed(-p.z(0) + 0.01, WrapAngle(p.z(1) + std::numbers::pi) - 0.002);
  bool flipped = false;
  const Vec2 nu = LineInnovation(observed, p, &flipped);
  EXPECT_TRUE(flipped);
  EXPECT_NEAR(nu(0), 0.01, 1e-12);
  EXPECT_NEAR(nu(1), -0.002, 1e-12);
  auto innovation = [&](const Pose2& r) {
    LinePrediction q = PredictLine(r, rho, alpha);
    return LineInnovation(observed, q);
  };
  // d(-nu) = dz in the flipped representation.
  const auto num =
      Numerical<3>([&](const Vec3& v) { return Vec2(-innovation(P(v))); }, robot.ToVector());
  EXPECT_LT((num - p.d_pose).norm(), 1e-6) << num << "\n" << p.d_pose;
}

TEST(LineModelTest, LineToParentJacobiansMatchNumericalAndInvertPrediction) {
  const Pose2 pose{-2.0, 0.5, 2.8};
  const double rho = 1.7, alpha = -0.9;
  const LineTransform t = LineToParent(pose, rho, alpha);
  // Predicting the parent line from the pose gives back the child line.
  const LinePrediction back = PredictLine(pose, t.line(0), t.line(1));
  EXPECT_NEAR(back.z(0), rho, 1e-12);
  EXPECT_NEAR(WrapAngle(back.z(1) - alpha), 0.0, 1e-12);
  const auto by_pose = Numerical<3>(
      [&](const Vec3& v) { return LineToParent(P(v), rho, alpha).line; }, pose.ToVector());
  const auto by_line = Numerical<2>(
      [&](const Vec2& l) { return LineToParent(pose, l(0), l(1)).line; }, Vec2(rho, alpha));
  EXPECT_LT((by_pose - t.d_pose).norm(), 1e-7) << by_pose << "\n" << t.d_pose;
  EXPECT_LT((by_line - t.d_line).norm(), 1e-7) << by_line << "\n" << t.d_line;
}

TEST(LineModelTest, CanonicalFormAndPositions) {
  double rho = -2.0, alpha = 0.5;
  EXPECT_TRUE(CanonicalizeLine(rho, alpha));
  EXPECT_DOUBLE_EQ(rho, 2.0);
  EXPECT_NEAR(alpha, 0.5 + std::numbers::pi - 2 * std::numbers::pi, 1e-12);
  const Vec2 p = PointOnLine(2.0, 0.3, 1.5);
  EXPECT_NEAR(p.x() * std::cos(0.3) + p.y() * std::sin(0.3), 2.0, 1e-12);
  EXPECT_NEAR(PositionAlongLine(0.3, p), 1.5, 1e-12);
}

}  // namespace
}  // namespace atlas
