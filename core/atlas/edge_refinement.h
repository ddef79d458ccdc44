#pragma once
// Edge refinement (paper, Section III-F, eq. 13-18).
//
// Two mature hypotheses in adjacent frames i and j, with robot poses x_i and x_j, observe the
// edge T_i^j (the pose of frame j in frame i):
//   T_i^j (+) x_j = x_i                                                        eq. 13
//   T_i^j = x_i (+) ((-) x_j)                                                  eq. 14
//   Sigma_ij = M_i Sigma_xi M_i^T + M_j Sigma_xj M_j^T,                        eq. 15
//   M_i = J1(x_i, (-)x_j),  M_j = J2(x_i, (-)x_j) J(-)(x_j).
// The cross covariance between the two maps' robot estimates is not kept, so the observation is
// fused with the existing edge by covariance intersection:
//   Sigma+ = [w Sigma_ij^-1 + (1 - w) Sigma_ij-^-1]^-1                         eq. 16
//   T+     = Sigma+ [w Sigma_ij^-1 T_ij + (1 - w) Sigma_ij-^-1 T_ij-]          eq. 17
//   w      = argmin det(Sigma+)                                                eq. 18
// eq. 17 as printed weights x_i and x_j with Sigma_xi^-1, Sigma_xj^-1; that is dimensionally a
// typo for the standard CI mean (Julier and Uhlmann), which is what is implemented: the two
// estimates of the same edge are weighted by their information. The angle of the observation is
// taken relative to the prior's angle before averaging. w is found by golden-section search on
// [0, 1]: det(w A + (1 - w) B) is log-concave in w, so det(Sigma+) is unimodal.
//
// Gate (our addition; the paper fuses every observation): CI is consistent only if both inputs
// estimate the same edge. When one of the two hypotheses is mislocalised, its observation can be
// metres and radians away from the edge, and CI would move the edge there (on mit-csail a
// refined Genesis edge moved 20 m). An observation whose difference from the edge has a squared
// Mahalanobis distance d2 = v^T (Sigma_ij + Sigma_ij-)^-1 v above the gate is rejected and the
// edge kept. The sum of the covariances is the covariance of the difference for independent
// inputs; positive correlation makes the true one smaller, so the gate only catches gross
// disagreement, which is what it is for.

#include <Eigen/LU>

#include "core/geometry/se2.h"

namespace atlas {

// eq. 14-15: the edge observation from the two robot poses.
UncertainPose EdgeObservation(const UncertainPose& x_i, const UncertainPose& x_j);

struct CovarianceIntersection {
  UncertainPose fused;
  double omega = 0.0;  // weight of the observation
};

// eq. 16-18. A (numerically) singular input dominates: a singular prior is kept (w = 0), a
// singular observation replaces it (w = 1).
CovarianceIntersection IntersectCovariances(const UncertainPose& observation,
                                            const UncertainPose& prior,
                                            double omega_tolerance = 1e-6);

enum class RefineResult { kAccepted, kRejected };

struct EdgeRefinement {
  RefineResult result = RefineResult::kRejected;
  CovarianceIntersection ci;  // valid when kAccepted
  double d2 = 0.0;            // squared Mahalanobis distance of observation and prior
};

// Gated eq. 16-18: rejected when d2 > gate_chi2 or the distance is not finite.
EdgeRefinement RefineEdge(const UncertainPose& observation, const UncertainPose& prior,
                          double gate_chi2);

}  // namespace atlas
