#pragma once
// The bootstrapping function w of eq. 12 (Section III-E): once a juvenile hypothesis has been
// seeded with a projected pose x_i* (eq. 10-11) and has accumulated scans interpreted with it,
// w solves the robot pose from the matched features ALONE, so that the new hypothesis stays
// statistically independent of the map-frame it came from.
//
// Contract of Bootstrap():
// - The seed (mean and covariance) is used only to propose correspondences: each observed
//   line is gated against each map line with the seed's uncertainty, and the pairings are
//   chosen by JCBB (jcbb.h); ambiguous observations are dropped. It also picks which of the
//   two representations (rho, alpha) / (-rho, alpha + pi) of a line is meant. The returned
//   pose does not depend on the seed otherwise: the heading is the weighted mean of the
//   matched angle differences, the position the weighted least-squares intersection of the
//   matched lines, refined by Gauss-Newton on all matches with weights from the observation
//   covariances only.
// - Typed outcome: kSolved; kTooFewMatches (fewer than min_matches unambiguous pairings);
//   kUnderconstrained (no two matched map lines differ in direction by min_angle_between:
//   e.g. only parallel corridor walls, position along them unknown); kInconsistent (the
//   residual fails the chi-square test at residual_gate with 2q - 3 dof).
// - Covariance: pose.cov = (H^T R^-1 H)^-1 (observations) + J_L Sigma_L J_L^T (map lines,
//   their marginals treated as independent). d_lines = J_L and observation_cov are exported so
//   that LineEkfMap::SetRobotPoseFromFeatures can keep the robot-feature cross covariances.

#include <Eigen/Core>
#include <vector>

#include "core/localmap/line_model.h"
#include "core/localmap/local_map.h"
#include "core/localmap/localmap_options.h"

namespace atlas {

// One accumulated scan: its lines in the robot frame at that scan, and the pose of that robot
// frame in the CURRENT robot frame (odometry since the scan) with its covariance.
struct BootstrapScan {
  Pose2 pose_in_current;
  Mat3 pose_cov = Mat3::Zero();
  std::vector<ObservedLine> lines;
};

enum class BootstrapStatus { kSolved, kTooFewMatches, kUnderconstrained, kInconsistent };

struct BootstrapMatch {
  int scan = -1;
  int line = -1;        // index into scans[scan].lines
  int feature = -1;     // index into the map's lines
  int feature_id = -1;  // MapLine::id
};

struct BootstrapResult {
  BootstrapStatus status = BootstrapStatus::kTooFewMatches;
  UncertainPose pose;  // the robot pose in the map-frame (valid when kSolved)
  std::vector<BootstrapMatch> matches;
  double residual_d2 = 0.0;
  int residual_dof = 0;
  // For LineEkfMap::SetRobotPoseFromFeatures: features (indices into the map's lines) and
  // d pose / d (rho, alpha) of each (3 x 2 blocks in that order), and the observation part of
  // the covariance.
  std::vector<int> feature_index;
  Eigen::Matrix<double, 3, Eigen::Dynamic> d_lines;
  Mat3 observation_cov = Mat3::Zero();
};

// w(M, Z) of eq. 12. `map` are the map-frame's lines (LocalMap::Lines()), `seed` the projected
// pose x_i* with its covariance. Options must be valid.
BootstrapResult Bootstrap(const std::vector<MapLine>& map, const std::vector<BootstrapScan>& scans,
                          const UncertainPose& seed, const BootstrapOptions& options,
                          const AssociationOptions& association);

}  // namespace atlas
