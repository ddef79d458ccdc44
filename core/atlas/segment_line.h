#pragma once
// Test and benchmark helper: the MapLine of a wall segment from p to q, in the (rho >= 0, alpha)
// form the local maps use, with a diagonal (rho, alpha) covariance.

#include <cmath>

#include "core/localmap/local_map.h"

namespace atlas {

inline MapLine SegmentLine(const Vec2& p, const Vec2& q, double sigma_rho, double sigma_alpha) {
  MapLine l;
  const Vec2 d = (q - p).normalized();
  Vec2 n(-d.y(), d.x());
  double rho = n.dot(p);
  if (rho < 0) {
    n = -n;
    rho = -rho;
  }
  l.rho = rho;
  l.alpha = std::atan2(n.y(), n.x());
  l.cov = Vec2(sigma_rho * sigma_rho, sigma_alpha * sigma_alpha).asDiagonal();
  l.endpoint_a = p;
  l.endpoint_b = q;
  return l;
}

}  // namespace atlas
