#include "core/localmap/line_model.h"

#include <cmath>
#include <numbers>

namespace atlas {

bool CanonicalizeLine(double& rho, double& alpha) {
  bool flipped = false;
  if (rho < 0.0) {
    rho = -rho;
    alpha += std::numbers::pi;
    flipped = true;
  }
  alpha = WrapAngle(alpha);
  return flipped;
}

Vec2 LineThroughPoints(const Vec2& a, const Vec2& b) {
  const Vec2 d = (b - a).normalized();
  double alpha = std::atan2(d.x(), -d.y());  // the normal
  double rho = a.x() * std::cos(alpha) + a.y() * std::sin(alpha);
  CanonicalizeLine(rho, alpha);
  return Vec2(rho, alpha);
}

LineTransform LineToParent(const Pose2& pose, double rho_c, double alpha_c) {
  LineTransform t;
  const double a = alpha_c + pose.theta;
  const double c = std::cos(a), s = std::sin(a);
  const double dr_da = -pose.x * s + pose.y * c;
  t.line = Vec2(rho_c + pose.x * c + pose.y * s, a);
  t.d_pose << c, s, dr_da, 0.0, 0.0, 1.0;
  t.d_line << 1.0, dr_da, 0.0, 1.0;
  return t;
}

ObservedLine ObservedLineToParent(const Pose2& pose, const ObservedLine& line) {
  const LineTransform t = LineToParent(pose, line.rho, line.alpha);
  ObservedLine out = line;
  out.rho = t.line(0);
  out.alpha = t.line(1);
  out.cov = t.d_line * line.cov * t.d_line.transpose();
  if (CanonicalizeLine(out.rho, out.alpha)) out.cov(0, 1) = out.cov(1, 0) = -out.cov(0, 1);
  out.endpoint_a = pose.TransformPoint(line.endpoint_a);
  out.endpoint_b = pose.TransformPoint(line.endpoint_b);
  return out;
}

LinePrediction PredictLine(const Pose2& robot, double rho, double alpha) {
  LinePrediction p;
  const double c = std::cos(alpha), s = std::sin(alpha);
  p.z = Vec2(rho - robot.x * c - robot.y * s, alpha - robot.theta);
  p.d_pose << -c, -s, 0.0, 0.0, 0.0, -1.0;
  p.d_line << 1.0, robot.x * s - robot.y * c, 0.0, 1.0;
  return p;
}

Vec2 LineInnovation(const Vec2& observed, LinePrediction& prediction, bool* flipped) {
  double dalpha = WrapAngle(observed(1) - prediction.z(1));
  const bool flip = std::abs(dalpha) > 0.5 * std::numbers::pi;
  if (flipped != nullptr) *flipped = flip;
  if (flip) {
    prediction.z(0) = -prediction.z(0);
    prediction.z(1) = WrapAngle(prediction.z(1) + std::numbers::pi);
    prediction.d_pose.row(0) *= -1.0;
    prediction.d_line.row(0) *= -1.0;
    dalpha = WrapAngle(observed(1) - prediction.z(1));
  }
  return Vec2(observed(0) - prediction.z(0), dalpha);
}

double PositionAlongLine(double alpha, const Vec2& p) {
  return -p.x() * std::sin(alpha) + p.y() * std::cos(alpha);
}

Vec2 PointOnLine(double rho, double alpha, double t) {
  const double c = std::cos(alpha), s = std::sin(alpha);
  return Vec2(rho * c - t * s, rho * s + t * c);
}

}  // namespace atlas
