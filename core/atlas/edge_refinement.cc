#include "core/atlas/edge_refinement.h"

#include <Eigen/LU>
#include <cmath>
#include <limits>

namespace atlas {

UncertainPose EdgeObservation(const UncertainPose& x_i, const UncertainPose& x_j) {
  return Compose(x_i, Inverse(x_j));
}

namespace {

bool Invertible(const Mat3& m) {
  const double scale = m.cwiseAbs().maxCoeff();
  return scale > 0.0 && std::isfinite(scale) && m.determinant() > 1e-18 * scale * scale * scale;
}

}  // namespace

CovarianceIntersection IntersectCovariances(const UncertainPose& observation,
                                            const UncertainPose& prior, double tol) {
  if (!Invertible(prior.cov)) return {prior, 0.0};
  if (!Invertible(observation.cov)) return {observation, 1.0};
  const Mat3 a = observation.cov.inverse();
  const Mat3 b = prior.cov.inverse();
  // Maximise det(w A + (1 - w) B), i.e. minimise det(Sigma+).
  const auto info_det = [&](double w) { return (w * a + (1.0 - w) * b).determinant(); };
  const double g = (std::sqrt(5.0) - 1.0) / 2.0;
  double lo = 0.0, hi = 1.0;
  double x1 = hi - g * (hi - lo), x2 = lo + g * (hi - lo);
  double f1 = info_det(x1), f2 = info_det(x2);
  while (hi - lo > tol) {
    if (f1 < f2) {
      lo = x1;
      x1 = x2;
      f1 = f2;
      x2 = lo + g * (hi - lo);
      f2 = info_det(x2);
    } else {
      hi = x2;
      x2 = x1;
      f2 = f1;
      x1 = hi - g * (hi - lo);
      f1 = info_det(x1);
    }
  }
  double w = 0.5 * (lo + hi);
  // The optimum may sit at an end of the interval.
  if (info_det(0.0) >= info_det(w)) w = 0.0;
  if (info_det(1.0) >= info_det(w)) w = 1.0;

  const Mat3 info = w * a + (1.0 - w) * b;
  const Mat3 cov = info.inverse();
  Vec3 obs = observation.mean.ToVector();
  const Vec3 pri = prior.mean.ToVector();
  obs.z() = pri.z() + WrapAngle(obs.z() - pri.z());
  const Vec3 mean = cov * (w * a * obs + (1.0 - w) * b * pri);
  CovarianceIntersection out;
  out.fused.mean = Pose2::FromVector(mean);
  out.fused.cov = 0.5 * (cov + cov.transpose());
  out.omega = w;
  return out;
}

EdgeRefinement RefineEdge(const UncertainPose& observation, const UncertainPose& prior,
                          double gate_chi2) {
  EdgeRefinement out;
  Vec3 v = observation.mean.ToVector() - prior.mean.ToVector();
  v.z() = WrapAngle(v.z());
  const Mat3 s = observation.cov + prior.cov;
  out.d2 = Invertible(s) ? v.dot(s.inverse() * v) : std::numeric_limits<double>::infinity();
  if (!(out.d2 <= gate_chi2)) return out;
  out.result = RefineResult::kAccepted;
  out.ci = IntersectCovariances(observation, prior);
  return out;
}

}  // namespace atlas
