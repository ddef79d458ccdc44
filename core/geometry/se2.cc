#include "core/geometry/se2.h"

namespace atlas {

double WrapAngle(double a) {
  constexpr double kPi = std::numbers::pi;
  if (a > -kPi && a <= kPi) return a;
  a = std::fmod(a + kPi, 2.0 * kPi);
  if (a <= 0.0) a += 2.0 * kPi;
  return a - kPi;
}

Vec2 Pose2::TransformPoint(const Vec2& p) const {
  const double c = std::cos(theta), s = std::sin(theta);
  return Vec2(x + c * p.x() - s * p.y(), y + s * p.x() + c * p.y());
}

Pose2 Compose(const Pose2& a, const Pose2& b) {
  const double c = std::cos(a.theta), s = std::sin(a.theta);
  return Pose2{a.x + c * b.x - s * b.y, a.y + s * b.x + c * b.y, WrapAngle(a.theta + b.theta)};
}

Pose2 Inverse(const Pose2& a) {
  const double c = std::cos(a.theta), s = std::sin(a.theta);
  return Pose2{-c * a.x - s * a.y, s * a.x - c * a.y, WrapAngle(-a.theta)};
}

Pose2 Between(const Pose2& a, const Pose2& b) {
  const double c = std::cos(a.theta), s = std::sin(a.theta);
  const double dx = b.x - a.x, dy = b.y - a.y;
  return Pose2{c * dx + s * dy, -s * dx + c * dy, WrapAngle(b.theta - a.theta)};
}

Pose2 InterpolatePose(const Pose2& a, const Pose2& b, double f) {
  return Pose2{a.x + f * (b.x - a.x), a.y + f * (b.y - a.y),
               WrapAngle(a.theta + f * WrapAngle(b.theta - a.theta))};
}

Mat3 ComposeJacobianA(const Pose2& a, const Pose2& b) {
  const double c = std::cos(a.theta), s = std::sin(a.theta);
  Mat3 j = Mat3::Identity();
  j(0, 2) = -s * b.x - c * b.y;
  j(1, 2) = c * b.x - s * b.y;
  return j;
}

Mat3 ComposeJacobianB(const Pose2& a) {
  const double c = std::cos(a.theta), s = std::sin(a.theta);
  Mat3 j;
  j << c, -s, 0, s, c, 0, 0, 0, 1;
  return j;
}

Mat3 InverseJacobian(const Pose2& a) {
  const double c = std::cos(a.theta), s = std::sin(a.theta);
  Mat3 j;
  j << -c, -s, s * a.x - c * a.y,  //
      s, -c, c * a.x + s * a.y,    //
      0, 0, -1;
  return j;
}

UncertainPose Compose(const UncertainPose& a, const UncertainPose& b) {
  const Mat3 j1 = ComposeJacobianA(a.mean, b.mean);
  const Mat3 j2 = ComposeJacobianB(a.mean);
  return UncertainPose{Compose(a.mean, b.mean),
                       j1 * a.cov * j1.transpose() + j2 * b.cov * j2.transpose()};
}

UncertainPose Inverse(const UncertainPose& a) {
  const Mat3 j = InverseJacobian(a.mean);
  return UncertainPose{Inverse(a.mean), j * a.cov * j.transpose()};
}

UncertainPose Between(const UncertainPose& a, const UncertainPose& b) {
  return Compose(Inverse(a), b);
}

}  // namespace atlas
