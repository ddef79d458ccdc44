#include "core/geometry/se2.h"

#include <gtest/gtest.h>

#include <Eigen/Cholesky>
#include <cmath>
#include <functional>
#include <random>

namespace atlas {
namespace {

// Central differences of f at p, column k = df/dp_k; the angle of the result is wrapped.
Mat3 NumericJacobian(const std::function<Pose2(const Pose2&)>& f, const Pose2& p) {
  constexpr double h = 1e-6;
  Mat3 j;
  for (int k = 0; k < 3; ++k) {
    Vec3 plus = p.ToVector(), minus = p.ToVector();
    plus[k] += h;
    minus[k] -= h;
    const Pose2 fp = f(Pose2{plus.x(), plus.y(), plus.z()});
    const Pose2 fm = f(Pose2{minus.x(), minus.y(), minus.z()});
    j(0, k) = (fp.x - fm.x) / (2 * h);
    j(1, k) = (fp.y - fm.y) / (2 * h);
    j(2, k) = WrapAngle(fp.theta - fm.theta) / (2 * h);
  }
  return j;
}

Pose2 RandomPose(std::mt19937& rng) {
  std::uniform_real_distribution<double> xy(-20.0, 20.0);
  std::uniform_real_distribution<double> th(-3.14, 3.14);
  return Pose2{xy(rng), xy(rng), th(rng)};
}

TEST(WrapAngle, StaysInHalfOpenInterval) {
  EXPECT_DOUBLE_EQ(WrapAngle(0.0), 0.0);
  EXPECT_NEAR(WrapAngle(3 * std::numbers::pi), std::numbers::pi, 1e-12);
  EXPECT_NEAR(WrapAngle(-std::numbers::pi), std::numbers::pi, 1e-12);
  EXPECT_NEAR(WrapAngle(7.0), 7.0 - 2 * std::numbers::pi, 1e-12);
  EXPECT_NEAR(WrapAngle(-7.0), -7.0 + 2 * std::numbers::pi, 1e-12);
  for (double a = -50; a < 50; a += 0.37) {
    const double w = WrapAngle(a);
    EXPECT_GT(w, -std::numbers::pi);
    EXPECT_LE(w, std::numbers::pi);
    EXPECT_NEAR(std::cos(w), std::cos(a), 1e-9);
    EXPECT_NEAR(std::sin(w), std::sin(a), 1e-9);
  }
}

TEST(Se2, InterpolatePoseIsLinearAndTurnsTheShorterWay) {
  // From heading 3.0 to -2.9: 2 pi - 5.9 = 0.38 rad counter-clockwise, across +-pi.
  const Pose2 a{1.0, -2.0, 3.0};
  const Pose2 b{3.0, 2.0, -2.9};
  const Pose2 mid = InterpolatePose(a, b, 0.5);
  EXPECT_NEAR(mid.x, 2.0, 1e-12);
  EXPECT_NEAR(mid.y, 0.0, 1e-12);
  EXPECT_NEAR(mid.theta, 0.05 - M_PI, 1e-12);  // 3.0 + 0.19, wrapped; not through 0
  const Pose2 at_a = InterpolatePose(a, b, 0.0);
  EXPECT_NEAR(at_a.x, 1.0, 1e-12);
  EXPECT_NEAR(at_a.y, -2.0, 1e-12);
  EXPECT_NEAR(at_a.theta, 3.0, 1e-12);
  const Pose2 at_b = InterpolatePose(a, b, 1.0);
  EXPECT_NEAR(at_b.x, 3.0, 1e-12);
  EXPECT_NEAR(at_b.y, 2.0, 1e-12);
  EXPECT_NEAR(at_b.theta, -2.9, 1e-12);
  // Beyond b: extrapolated at the same rate.
  const Pose2 past = InterpolatePose(a, b, 1.5);
  EXPECT_NEAR(past.x, 4.0, 1e-12);
  EXPECT_NEAR(past.y, 4.0, 1e-12);
  EXPECT_NEAR(past.theta, M_PI - 5.85, 1e-12);
}

TEST(Se2, ComposeWithInverseIsIdentity) {
  std::mt19937 rng(1);
  for (int i = 0; i < 100; ++i) {
    const Pose2 a = RandomPose(rng);
    const Pose2 e = Compose(a, Inverse(a));
    EXPECT_NEAR(e.x, 0, 1e-12);
    EXPECT_NEAR(e.y, 0, 1e-12);
    EXPECT_NEAR(e.theta, 0, 1e-12);
    const Pose2 b = RandomPose(rng);
    const Pose2 ab = Compose(a, Between(a, b));
    EXPECT_NEAR(ab.x, b.x, 1e-9);
    EXPECT_NEAR(ab.y, b.y, 1e-9);
    EXPECT_NEAR(WrapAngle(ab.theta - b.theta), 0, 1e-12);
  }
}

TEST(Se2, ComposeKnownValue) {
  const Pose2 c = Compose(Pose2{1, 2, std::numbers::pi / 2}, Pose2{3, 0, 0.5});
  EXPECT_NEAR(c.x, 1.0, 1e-12);
  EXPECT_NEAR(c.y, 5.0, 1e-12);
  EXPECT_NEAR(c.theta, std::numbers::pi / 2 + 0.5, 1e-12);
}

TEST(Se2, JacobiansMatchNumericalDifferentiation) {
  std::mt19937 rng(7);
  for (int i = 0; i < 200; ++i) {
    const Pose2 a = RandomPose(rng), b = RandomPose(rng);
    const Mat3 j1 = NumericJacobian([&](const Pose2& p) { return Compose(p, b); }, a);
    const Mat3 j2 = NumericJacobian([&](const Pose2& p) { return Compose(a, p); }, b);
    const Mat3 ji = NumericJacobian([](const Pose2& p) { return Inverse(p); }, a);
    EXPECT_LT((j1 - ComposeJacobianA(a, b)).cwiseAbs().maxCoeff(), 1e-6) << i;
    EXPECT_LT((j2 - ComposeJacobianB(a)).cwiseAbs().maxCoeff(), 1e-6) << i;
    EXPECT_LT((ji - InverseJacobian(a)).cwiseAbs().maxCoeff(), 1e-6) << i;
  }
}

TEST(Se2, CovariancePropagationMatchesMonteCarlo) {
  std::mt19937 rng(3);
  UncertainPose a{Pose2{2.0, -1.0, 0.7}, Vec3(0.04, 0.09, 0.01).asDiagonal()};
  UncertainPose b{Pose2{5.0, 1.0, -0.3}, Vec3(0.01, 0.02, 0.005).asDiagonal()};
  const UncertainPose c = Compose(a, b);
  std::normal_distribution<double> n(0.0, 1.0);
  const Eigen::LLT<Mat3> la(a.cov), lb(b.cov);
  const int kSamples = 200000;
  Mat3 sample_cov = Mat3::Zero();
  for (int i = 0; i < kSamples; ++i) {
    const Vec3 za(n(rng), n(rng), n(rng)), zb(n(rng), n(rng), n(rng));
    const Vec3 pa = a.mean.ToVector() + Mat3(la.matrixL()) * za;
    const Vec3 pb = b.mean.ToVector() + Mat3(lb.matrixL()) * zb;
    const Pose2 pc = Compose(Pose2{pa.x(), pa.y(), pa.z()}, Pose2{pb.x(), pb.y(), pb.z()});
    Vec3 d(pc.x - c.mean.x, pc.y - c.mean.y, WrapAngle(pc.theta - c.mean.theta));
    sample_cov += d * d.transpose();
  }
  sample_cov /= kSamples;
  // First-order propagation; small angle noise keeps the linearisation within a few percent.
  for (int r = 0; r < 3; ++r)
    for (int k = 0; k < 3; ++k)
      EXPECT_NEAR(sample_cov(r, k), c.cov(r, k), 0.06 * std::sqrt(c.cov(r, r) * c.cov(k, k)))
          << r << "," << k;
}

TEST(Se2, InverseCovarianceRoundTrips) {
  UncertainPose a{Pose2{2.0, -1.0, 0.7}, Mat3::Zero()};
  a.cov << 0.04, 0.01, 0.002, 0.01, 0.09, -0.003, 0.002, -0.003, 0.01;
  const UncertainPose back = Inverse(Inverse(a));
  EXPECT_LT((back.cov - a.cov).cwiseAbs().maxCoeff(), 1e-12);
  // Between(a, a) of independent copies: zero mean.
  const UncertainPose z = Between(a, a);
  EXPECT_NEAR(z.mean.x, 0, 1e-12);
  EXPECT_NEAR(z.mean.theta, 0, 1e-12);
}

}  // namespace
}  // namespace atlas
