#pragma once
// w of eq. 12 for the sonar-only atlas (paper, Section III-E): (M_i^new, x_i^new) = w(M_i, Z).
//
// Why: a juvenile seeded by traversal (eq. 10-11) runs on a clone of its frame's map with the
// robot at the seed x_i*, which comes from other frames across edges but enters the EKF as
// independent of frame i's features (the atlas keeps no correlation between frames). A trial
// map updated from it, adopted at maturation, carries that information into frame i at every
// re-entry (the robot NEES grew with the re-entries of a frame; docs/design.md, "Sonar local
// maps"). This
// w discards the trial map and solves from M_i, the frame's map as the juvenile found it, and
// the juvenile's readings Z alone; the seed only proposes correspondences, as for the laser's
// w (core/localmap/bootstrap.h).
//
// - Z: the juvenile's sonar readings with the odometry increments between them. The robot frame
//   of reading k is placed in the frame of the last reading, p_k, by composing the increments
//   backwards, each with the odometry noise Q(u) of the map's Predict (LineEkfMap::OdometryNoise).
// - Model: return j of reading k, paired with map line l, r_j = h(x (+) p_k, m_j, L_l) + v_j
//   (PredictSonarRange with the map's own cone scale, in-cone echoes unless `edge_echoes`; v_j
//   the map's range noise, variance var_j), x the robot pose at the last reading in the map
//   frame.
// - Solution: Gauss-Newton over x alone, the lines held at M_i's estimates:
//   x = argmin sum_j (r_j - h_j)^2 / var_j. Linearised at the solution, with H = dh/dx,
//   W = diag(1 / var_j), A = H^T W H: dx = A^-1 H^T W (dv - H_L dL - H_u du), so
//     Cov(x) = A^-1 + J_u Q J_u^T  (readings and odometry: independent of the map)
//              + J_L P_LL J_L^T,   Cov(x, L) = J_L P_LL,   J_L = -A^-1 H^T W H_L,
//   which SonarLocalMap::SetRobotPoseFromFeatures writes into a clone of M_i: that clone is
//   M_i^new. The readings of Z enter it through x only (their information on the features
//   beyond the pose is dropped: conservative, never counted twice), and nothing of the seed.
// - Association, as the map's update pairs returns (SonarLocalMap::UpdateSonar: the line whose
//   prediction echoes within its extent plus max_extent_gap, chi-square gate `update.gate`,
//   unambiguous by `update.ambiguity_margin`), at an estimate with a covariance: first the
//   start estimate, then each solution with its covariance, until the pairing no longer changes
//   (at most `rounds`). The result depends on the start only through the first pairing; once
//   the pairing is the one made at the solution, two starts give the same answer (test
//   SolutionDoesNotDependOnTheSeed).
// - The start estimate (`dead_reckoned_start`): the seed x_i* of eq. 10-11 moved through Z's
//   increments by dead reckoning, its covariance grown by their odometry noise Q(u); not the
//   juvenile's current pose. The juvenile's clone of M_i, updated from the seed by its own
//   readings, can be drawn during probation to lines that are not where it is (sonar maps hold
//   phantom lines), and w then started there paired its readings as the clone
//   did. Measured on the simulated building (24 transducers, 100 runs): started at the juvenile's
//   pose, 73 of 766 solutions had a robot NEES above 20 and 31 above 50; 65 of those 73 had started
//   from a juvenile pose already above 9.35, whose seed had been below 9.35 in 50. From the
//   dead-reckoned seed: 49 of 717 above 20, 12 above 50.
// - Outcome: kSolved; kUndetermined while Z does not fix the pose: fewer than `min_returns`
//   paired returns, A singular, or Cov(x) with a position standard deviation (largest axis)
//   above max_sigma_xy or a heading one above max_sigma_theta (one wall or parallel walls leave
//   the position along them free); the atlas then keeps accumulating readings and kills the
//   juvenile at the end of probation (eq. 12: "an explicit solution cannot be computed").
//   kFailed: the paired returns contradict the solution (sum of squared residuals over their
//   variances, line uncertainty included, beyond the `residual_gate` chi-square quantile with
//   m - 3 dof), the solution lies outside the start estimate's gate (x - start with covariance
//   Cov(start) + Cov(x), 3 dof, `residual_gate`: the readings place the robot elsewhere, which is
//   another hypothesis than the one seeded; on the simulated building, without this test, w
//   once moved a juvenile 10.5 m along a corridor, sigma 0.15 m), Gauss-Newton did not converge,
//   or `frame_map` is not a SonarLocalMap. The start estimate only rejects; it never enters x.
// Work: at most rounds x max_iterations passes over (returns of Z) x (lines of M_i); Z is
// bounded by the probation (LifecycleOptions::probation_scans).
//
// For sonar-only atlases (FromSonar: Z holds the sonar steps; odometry between them must be in
// their increments, so an atlas that also steps laser scans would lose the scans' increments).

#include <string>
#include <vector>

#include "core/atlas/hypothesis.h"

namespace atlas {

// Probation (LifecycleOptions::probation_scans, in sonar readings) of a sonar-only atlas's
// juveniles with this w: at 10 readings of about 4 returns each, Z rarely fixes the pose within
// the default 8 (building: 307 of 428 juveniles killed by w); measured with in-cone pairings:
// probation 16 / 30, robot NEES building 6.31 / 5.96, alcove loop 7.65 / 6.49.
inline constexpr int kSonarBootstrapProbation = 30;

struct SonarBootstrapOptions {
  int min_returns = 8;           // paired returns needed to solve
  double max_sigma_xy = 0.3;     // metres, largest axis of Cov(x)'s position block
  double max_sigma_theta = 0.1;  // radians
  double residual_gate = 0.999;  // chi-square probability
  int rounds = 3;                // association rounds
  int max_iterations = 10;       // Gauss-Newton iterations per round
  // Whether returns may be paired as edge-of-cone echoes (SonarModelOptions::edge_incidence),
  // as the map's update pairs them. Off: in-cone (tangent model) pairings only. The edge terms
  // tie the range to the heading strongly and the jambs and corners that echo at the cone's
  // edge are the model's worst fits; with them w's solutions were further off than their
  // covariance (simulated alcove loop: robot NEES 20.1, 1 gross false closure; in-cone only:
  // 6.49, none gross; building 6.69 -> 5.96).
  bool edge_echoes = false;
  // The start estimate (see above): the seed moved by Z's odometry (true), or the juvenile's
  // current pose (false; docs/design.md, "Sonar local maps").
  bool dead_reckoned_start = true;
  std::string Validate() const;  // empty when valid
};

// The outcome of w with the diagnostics the tests and the evaluation look at.
struct SonarBootstrapResult {
  BootstrapOutcome outcome = BootstrapOutcome::kFailed;
  UncertainPose pose;  // Cov(x) above (when solved)
  int paired = 0;      // returns paired at the last round
  int rounds = 0;
  double residual_d2 = 0.0;
  std::vector<int> feature_index;  // lines of M_i used (indices into Lines()), in d_lines order
  Eigen::Matrix<double, 3, Eigen::Dynamic> d_lines;  // J_L, 3 x 2 per used line (canonical)
  Mat3 observation_cov = Mat3::Zero();               // A^-1 + J_u Q J_u^T
};

class SonarMapBootstrapper final : public PoseBootstrapper {
 public:
  // `options` must be valid.
  explicit SonarMapBootstrapper(const SonarBootstrapOptions& options = SonarBootstrapOptions());

  // w(M_i, Z): `map` is the juvenile's trial map, `frame_map` M_i (a SonarLocalMap), `seed` the
  // juvenile's x_i*; the start estimate comes from `seed` or `map` (dead_reckoned_start). When
  // solved, the result's map is M_i^new.
  PoseBootstrap Solve(const LocalMap& map, const LocalMap& frame_map,
                      const std::vector<JuvenileScan>& z, const UncertainPose& seed) const override;

  // `seed` moved through Z's increments (the odometry noise of `frame_map`'s options, which
  // must be a SonarLocalMap's): the start estimate of dead_reckoned_start.
  static UncertainPose DeadReckonedSeed(const LocalMap& frame_map, const UncertainPose& seed,
                                        const std::vector<JuvenileScan>& z);
  bool FromSonar() const override { return true; }

  // The solution alone, from the start estimate `start` (mean and covariance: the first
  // association's gate) against `frame_map`'s lines.
  SonarBootstrapResult SolvePose(const LocalMap& frame_map, const UncertainPose& start,
                                 const std::vector<JuvenileScan>& z) const;

 private:
  SonarBootstrapOptions o_;
};

}  // namespace atlas
