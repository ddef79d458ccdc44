#include "core/atlas/edge_refinement.h"

#include <gtest/gtest.h>

namespace atlas {
namespace {

// Worked by hand. Observation: mean (1, 0, 0), Sigma = diag(1, 4, 1); prior: mean (0, 1, 0),
// Sigma = diag(4, 1, 1). Informations A = diag(1, 1/4, 1), B = diag(1/4, 1, 1).
//   det(w A + (1 - w) B) = (1/4 + 3w/4)(1 - 3w/4) * 1,
//   d/dw = 3/4 (1 - 3w/4) - 3/4 (1/4 + 3w/4) = 0  =>  w = 1/2,
//   Sigma+ = diag(1/0.625, 1/0.625, 1) = diag(1.6, 1.6, 1),
//   T+ = Sigma+ (1/2 A (1,0,0) + 1/2 B (0,1,0)) = Sigma+ (0.5, 0.5, 0) = (0.8, 0.8, 0).
TEST(CovarianceIntersection, WorkedExample) {
  UncertainPose obs{Pose2{1, 0, 0}, Vec3(1, 4, 1).asDiagonal()};
  UncertainPose prior{Pose2{0, 1, 0}, Vec3(4, 1, 1).asDiagonal()};
  const CovarianceIntersection ci = IntersectCovariances(obs, prior, 1e-9);
  EXPECT_NEAR(ci.omega, 0.5, 1e-6);
  EXPECT_NEAR(ci.fused.mean.x, 0.8, 1e-6);
  EXPECT_NEAR(ci.fused.mean.y, 0.8, 1e-6);
  EXPECT_NEAR(ci.fused.mean.theta, 0.0, 1e-9);
  const Mat3 expect = Vec3(1.6, 1.6, 1.0).asDiagonal();
  EXPECT_LT((ci.fused.cov - expect).cwiseAbs().maxCoeff(), 1e-6);
  // The fused determinant is no larger than either input's (eq. 18 at the ends).
  EXPECT_LE(ci.fused.cov.determinant(), obs.cov.determinant());
  EXPECT_LE(ci.fused.cov.determinant(), prior.cov.determinant());
}

// A second worked example with unequal gains: Sigma_obs = diag(1, 1, 1), Sigma_prior =
// diag(9, 9, 1) (same angle variance). det(w I + (1-w) diag(1/9,1/9,1)) =
// (1/9 + 8w/9)^2 is increasing in w, so w = 1 and the observation is taken whole.
TEST(CovarianceIntersection, DominatingObservationTakesAll) {
  UncertainPose obs{Pose2{2, -1, 0.3}, Mat3::Identity()};
  UncertainPose prior{Pose2{0, 0, 0}, Vec3(9, 9, 1).asDiagonal()};
  const CovarianceIntersection ci = IntersectCovariances(obs, prior);
  EXPECT_NEAR(ci.omega, 1.0, 1e-9);
  EXPECT_NEAR(ci.fused.mean.x, 2.0, 1e-9);
  EXPECT_NEAR(ci.fused.mean.theta, 0.3, 1e-9);
}

TEST(CovarianceIntersection, AnglesAreAveragedAcrossTheWrap) {
  UncertainPose obs{Pose2{0, 0, 3.1}, Vec3(1, 4, 1).asDiagonal()};
  UncertainPose prior{Pose2{0, 0, -3.1}, Vec3(4, 1, 1).asDiagonal()};
  const CovarianceIntersection ci = IntersectCovariances(obs, prior);
  EXPECT_NEAR(std::abs(ci.fused.mean.theta), 3.14159, 1e-3);
}

TEST(CovarianceIntersection, SingularInputs) {
  UncertainPose obs{Pose2{1, 0, 0}, Mat3::Identity()};
  UncertainPose zero{Pose2{0, 1, 0}, Mat3::Zero()};
  EXPECT_EQ(IntersectCovariances(obs, zero).omega, 0.0);
  EXPECT_EQ(IntersectCovariances(obs, zero).fused.mean.y, 1.0);
  EXPECT_EQ(IntersectCovariances(zero, obs).omega, 1.0);
}

TEST(EdgeObservation, Eq14And15) {
  UncertainPose xi{Pose2{4, 2, 0.9}, Vec3(0.04, 0.02, 0.01).asDiagonal()};
  UncertainPose xj{Pose2{-1, 3, -0.4}, Vec3(0.01, 0.03, 0.02).asDiagonal()};
  const UncertainPose t = EdgeObservation(xi, xj);
  // eq. 13: T (+) x_j = x_i.
  const Pose2 back = Compose(t.mean, xj.mean);
  EXPECT_NEAR(back.x, xi.mean.x, 1e-12);
  EXPECT_NEAR(back.y, xi.mean.y, 1e-12);
  EXPECT_NEAR(back.theta, xi.mean.theta, 1e-12);
  // eq. 15 written out.
  const Pose2 inv_j = Inverse(xj.mean);
  const Mat3 mi = ComposeJacobianA(xi.mean, inv_j);
  const Mat3 mj = ComposeJacobianB(xi.mean) * InverseJacobian(xj.mean);
  const Mat3 expect = mi * xi.cov * mi.transpose() + mj * xj.cov * mj.transpose();
  EXPECT_LT((t.cov - expect).cwiseAbs().maxCoeff(), 1e-14);
}

// The gate: d2 = v^T (Sigma_obs + Sigma_prior)^-1 v. Observation (1, 0, 0.2) against the prior
// (0, 0, 0), both diag(0.5, 0.5, 0.01): Sigma = diag(1, 1, 0.02), d2 = 1 + 0 + 0.04 / 0.02 = 3.
TEST(RefineEdge, GateDistanceWorkedExample) {
  UncertainPose obs{Pose2{1, 0, 0.2}, Vec3(0.5, 0.5, 0.01).asDiagonal()};
  UncertainPose prior{Pose2{0, 0, 0}, Vec3(0.5, 0.5, 0.01).asDiagonal()};
  const EdgeRefinement r = RefineEdge(obs, prior, 16.27);
  EXPECT_NEAR(r.d2, 3.0, 1e-9);
  ASSERT_EQ(r.result, RefineResult::kAccepted);
  const CovarianceIntersection ci = IntersectCovariances(obs, prior);
  EXPECT_EQ(r.ci.fused.mean.x, ci.fused.mean.x);
  EXPECT_EQ(r.ci.omega, ci.omega);
  // The same observation with a gate below 3 is rejected.
  EXPECT_EQ(RefineEdge(obs, prior, 2.9).result, RefineResult::kRejected);
}

// mit-csail's case: a mislocalised hypothesis observes the edge 20 m and 2 rad away. Fused, CI
// would move the edge there; gated, the observation is rejected and the caller keeps the edge.
TEST(RefineEdge, GrossDisagreementIsRejected) {
  UncertainPose prior{Pose2{5.7, -9.9, -1.34}, Vec3(0.25, 0.09, 0.06).asDiagonal()};
  UncertainPose obs{Pose2{-6.4, 6.6, 2.13}, Vec3(0.3, 0.3, 0.1).asDiagonal()};
  const EdgeRefinement r = RefineEdge(obs, prior, 16.27);
  EXPECT_EQ(r.result, RefineResult::kRejected);
  EXPECT_GT(r.d2, 100.0);
  // Angles are compared across the wrap: -3.1 and 3.1 are 0.083 rad apart, inside the gate.
  UncertainPose a{Pose2{0, 0, 3.1}, Vec3(0.1, 0.1, 0.01).asDiagonal()};
  UncertainPose b{Pose2{0, 0, -3.1}, Vec3(0.1, 0.1, 0.01).asDiagonal()};
  EXPECT_EQ(RefineEdge(a, b, 16.27).result, RefineResult::kAccepted);
  // A singular sum (both exact) cannot be gated: rejected, not fused.
  UncertainPose exact{Pose2{0, 0, 0}, Mat3::Zero()};
  EXPECT_EQ(RefineEdge(exact, exact, 16.27).result, RefineResult::kRejected);
}

}  // namespace
}  // namespace atlas
