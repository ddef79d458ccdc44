#include "core/sonar/sonar_geometry.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include "core/localmap/line_model.h"

namespace atlas {

SonarRangePrediction PredictSonarRange(const Pose2& robot, const SonarTransducer& mount, double rho,
                                       double alpha, double edge_incidence) {
  SonarRangePrediction p;
  const Pose2 s = Compose(robot, mount.pose);
  const double c = std::cos(alpha), sn = std::sin(alpha);
  const double e = rho - s.x * c - s.y * sn;  // signed distance, transducer to line along n
  const double sign = e >= 0.0 ? 1.0 : -1.0;
  p.range = std::abs(e);
  const double normal = sign > 0.0 ? alpha : alpha + std::numbers::pi;
  p.incidence = WrapAngle(normal - s.theta);
  p.in_cone = std::abs(p.incidence) <= 0.5 * mount.beam_width;
  p.foot = Vec2(s.x, s.y) + e * Vec2(c, sn);
  // d(s.x, s.y)/d(robot): identity in x, y; d/dtheta = (-mx sin - my cos, mx cos - my sin).
  const double ct = std::cos(robot.theta), st = std::sin(robot.theta);
  const double dsx_dth = -mount.pose.x * st - mount.pose.y * ct;
  const double dsy_dth = mount.pose.x * ct - mount.pose.y * st;
  p.d_pose << -sign * c, -sign * sn, -sign * (c * dsx_dth + sn * dsy_dth);
  p.d_line << sign, sign * (s.x * sn - s.y * c);
  const double half = 0.5 * mount.beam_width;
  const double psi = std::abs(p.incidence) - half;
  if (p.in_cone || !(psi <= edge_incidence)) return p;
  p.edge_echo = true;
  const double cpsi = std::cos(psi);
  const double d = p.range;
  p.range = d / cpsi;
  const double edge = s.theta + (p.incidence >= 0.0 ? half : -half);
  p.foot = Vec2(s.x, s.y) + p.range * Vec2(std::cos(edge), std::sin(edge));
  // r = d / cos(psi), psi = |phi| - h, phi = normal - robot.theta - mount.theta.
  const double k = (p.incidence >= 0.0 ? 1.0 : -1.0) * d * std::sin(psi) / (cpsi * cpsi);
  p.d_pose /= cpsi;
  p.d_line /= cpsi;
  p.d_pose(2) -= k;
  p.d_line(1) += k;
  return p;
}

bool ConeFootprint(const Pose2& sensor, double half, double rho, double alpha, double& lo,
                   double& hi) {
  const Vec2 n(std::cos(alpha), std::sin(alpha)), along(-std::sin(alpha), std::cos(alpha));
  const double e = rho - sensor.x * n.x() - sensor.y * n.y();  // signed distance along n
  double t[2];
  int crossing = 0;
  for (int i = 0; i < 2; ++i) {
    const double a = sensor.theta + (i == 0 ? -half : half);
    const Vec2 u(std::cos(a), std::sin(a));
    const double den = u.dot(n);
    if (den * e > 0.0) {
      const double dist = e / den;
      t[i] = PositionAlongLine(alpha, Vec2(sensor.x, sensor.y) + dist * u);
      ++crossing;
    } else {
      t[i] = u.dot(along) >= 0.0 ? std::numeric_limits<double>::infinity()
                                 : -std::numeric_limits<double>::infinity();
    }
  }
  if (crossing == 0) return false;  // (a cone narrower than 180 degrees)
  lo = std::min(t[0], t[1]);
  hi = std::max(t[0], t[1]);
  return true;
}

Vec2 TangentLine(const Pose2& sensor, double range, double phi) {
  const double a = sensor.theta + phi;
  double rho = sensor.x * std::cos(a) + sensor.y * std::sin(a) + range;
  double alpha = a;
  CanonicalizeLine(rho, alpha);
  return Vec2(rho, alpha);
}

int CommonTangentLines(const Pose2& s1, double r1, double h1, const Pose2& s2, double r2, double h2,
                       Vec2 out[2]) {
  // Oriented line n . p = rho with rho - n . c_i = r_i: n . (c1 - c2) = r2 - r1.
  const Vec2 d(s1.x - s2.x, s1.y - s2.y);
  const double len = d.norm();
  if (len < 1e-9) return 0;
  const double ratio = (r2 - r1) / len;
  if (std::abs(ratio) > 1.0) return 0;
  const double beta = std::atan2(d.y(), d.x());
  const double gamma = std::acos(ratio);
  int count = 0;
  for (const double a : {beta + gamma, beta - gamma}) {
    if (std::abs(WrapAngle(a - s1.theta)) > h1 || std::abs(WrapAngle(a - s2.theta)) > h2) continue;
    if (count == 1 && gamma < 1e-12) break;
    double rho = s1.x * std::cos(a) + s1.y * std::sin(a) + r1;
    double alpha = a;
    CanonicalizeLine(rho, alpha);
    out[count++] = Vec2(rho, alpha);
  }
  return count;
}

}  // namespace atlas
