#include "core/geometry/covariance.h"

#include <cmath>

namespace atlas {

bool IsPositiveDefiniteCovariance(const Mat3& cov) {
  if (!cov.allFinite()) return false;
  const double scale = cov.cwiseAbs().maxCoeff();
  if (!(scale > 0.0)) return false;
  if ((cov - cov.transpose()).cwiseAbs().maxCoeff() > 1e-9 * scale) return false;
  const double largest_variance = cov.diagonal().maxCoeff();
  if (!(largest_variance > 0.0)) return false;
  // Without pivoting, so that the pivots are those of the matrix as written.
  const Mat3 s = 0.5 * (cov + cov.transpose());
  double d[3];
  Mat3 l = Mat3::Identity();
  for (int j = 0; j < 3; ++j) {
    double v = s(j, j);
    for (int k = 0; k < j; ++k) v -= l(j, k) * l(j, k) * d[k];
    d[j] = v;
    if (!(v > 1e-14 * largest_variance)) return false;
    for (int i = j + 1; i < 3; ++i) {
      double w = s(i, j);
      for (int k = 0; k < j; ++k) w -= l(i, k) * l(j, k) * d[k];
      l(i, j) = w / v;
    }
  }
  return true;
}

}  // namespace atlas
