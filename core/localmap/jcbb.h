#pragma once
// Data association by Joint Compatibility Branch and Bound: J. Neira and J. D. Tardos, "Data
// Association in Stochastic Mapping Using the Joint Compatibility Test", IEEE Trans. Robotics
// and Automation 17(6), 2001 — the method the Atlas paper names for map matching (Section
// III-D) and used here for scan-to-map association.
//
// Input: the candidate pairings (observation j, feature i) that passed the individual
// compatibility test (Mahalanobis gate, plus any geometric check the caller applies) with
// their innovations nu_ji and innovation covariances S_ji, and the cross covariances
// H_a P H_b^T between pairings (JointCovariance).
//
// Search: depth first over observations (those with fewest candidates first); each observation
// is paired with one of its candidates or left unpaired. A hypothesis H with k pairings is
// jointly compatible when D^2_H = nu_H^T S_H^-1 nu_H < chi2_inv(joint_gate, 2k). D^2 is grown
// incrementally with a Cholesky factor of S_H (O(k^2) per node). Branches that cannot reach the
// best number of pairings are cut. The best hypothesis has the most pairings, then the smallest
// D^2. Work is bounded by a node budget.
//
// Ambiguity (Condition 2 of the paper): another jointly compatible hypothesis with as many
// pairings whose D^2 exceeds the best's by less than `ambiguity_margin` makes every observation
// on which the two differ ambiguous; such observations are reported and must not be used.
// If the budget runs out the search cannot prove uniqueness: status kBudgetExhausted, and
// the caller should not use the result.

#include <vector>

#include "core/localmap/line_model.h"

namespace atlas {

struct CandidatePair {
  int observation = -1;
  int feature = -1;
  Vec2 innovation = Vec2::Zero();
  Mat2 S = Mat2::Identity();  // innovation covariance, observation noise included
  double d2 = 0.0;            // individual Mahalanobis distance squared
  int tag = -1;               // the caller's own index (e.g. into its Jacobians)
};

// Cross covariance between the predicted measurements of two pairings of different
// observations: H_a P H_b^T (2x2).
class JointCovariance {
 public:
  virtual ~JointCovariance() = default;
  virtual Mat2 Cross(const CandidatePair& a, const CandidatePair& b) const = 0;
};

struct JcbbOptions {
  double joint_gate = 0.99;
  int node_budget = 256;
  bool allow_shared_features = true;
  double ambiguity_margin = 4.0;
};

enum class AssociationStatus { kUnique, kAmbiguous, kBudgetExhausted };

struct JcbbResult {
  AssociationStatus status = AssociationStatus::kUnique;
  std::vector<int> feature_of;  // per observation: feature index, or -1 (unpaired)
  std::vector<int> pair_of;     // per observation: index into the candidates, or -1
  std::vector<bool> ambiguous;  // per observation: dropped because of an ambiguous rival
  int pairings = 0;             // in the best hypothesis, ambiguous ones included
  double joint_d2 = 0.0;
  int nodes = 0;
};

// Runs JCBB over `num_observations` observations. Candidates may come in any order.
JcbbResult Jcbb(int num_observations, const std::vector<CandidatePair>& candidates,
                const JointCovariance& cov, const JcbbOptions& options);

// Quantile of the chi-square distribution: P(X < x) = p with `dof` degrees of freedom
// (exact for 1 and 2 dof; Wilson-Hilferty otherwise: relative error below 1 % at 3 dof and
// below 0.2 % from 10 dof, for p in [0.9, 0.9999]).
double ChiSquareQuantile(double p, int dof);

}  // namespace atlas
