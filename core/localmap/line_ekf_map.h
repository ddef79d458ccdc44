#pragma once
// The paper's example local map (Sections II, IV): an Extended Kalman Filter over the robot
// pose and up to `capacity` infinite lines, in the coordinates of one map-frame (a stochastic
// map after Smith, Self and Cheeseman). Condition 1 asks that it be consistent.
//
// State: (x, y, theta, rho_1, alpha_1, ..., rho_N, alpha_N) with full covariance. Each line also
// carries the extent it was seen over (two endpoints on the line, not part of the state).
//
// - Predict(u): x <- x (+) u (SE(2) composition, se2.h); P_rr <- F P_rr F^T + G Q(u) G^T,
//   P_rl <- F P_rl, with F = d(x (+) u)/dx, G = d(x (+) u)/du and Q(u) the wheel-odometry noise
//   of OdometryNoiseOptions (variance linear in the distance each wheel rolled, plus floors
//   linear in distance and turn; the calibration errors wheel_scale_sigma, track_width_sigma
//   repeat every step, so their standard deviation grows linearly with the distance and turn
//   since the last update that matched a line).
// - Update(scan): lines are extracted (line_extraction.h) and moved to the robot frame, paired
//   with features by JCBB (jcbb.h) after a chi-square gate and a segment-extent check, and all
//   unambiguous pairings are applied in one batch update (z = PredictLine, line_model.h).
//   Ambiguous observations are neither used nor turned into features. If nothing paired, the
//   association runs again with the looser recovery_gate (a rare 3.5-4 sigma odometry error
//   would otherwise reject every pairing, and the pose would never be corrected again); its
//   result is used only with at least recovery_min_pairings jointly compatible pairings (a
//   lone pairing at the wide gate cannot be told from a spurious one; default 1: any).
// - New features: an unpaired observation that is not compatible with any feature even at the
//   looser new_feature_gate (no duplicate lines), long enough, becomes a feature with the
//   inverse model (LineToParent) and its cross covariances, if the caller allows it (mature
//   hypotheses only, Section III-E) and Complexity() < Capacity(); longest first.
// - Quality(): q of eq. 5 over the last QualityOptions::window scans (quality.h).
//
// Not thread-safe; copyable (Clone) and serialisable (Serialize: versioned binary image).

#include <Eigen/Core>
#include <vector>

#include "core/localmap/line_model.h"
#include "core/localmap/local_map.h"
#include "core/localmap/localmap_options.h"
#include "core/localmap/quality.h"

namespace atlas {

class LineEkfMap final : public LocalMap {
 public:
  // `options` must be valid (options.Validate() empty). The robot starts at the origin with
  // zero covariance (Genesis, Section III-C).
  explicit LineEkfMap(const LocalMapOptions& options = LocalMapOptions());

  std::unique_ptr<LocalMap> Clone() const override;
  void Predict(const Pose2& odometry_delta) override;
  void Predict(const Pose2& odometry_delta, const Mat3& covariance) override;
  ScanUpdate Update(const LaserScan& scan, bool allow_new_features) override;
  // Update(scan) on observation.RobotFrameLines(Options().extraction).
  ScanUpdate Update(const ScanObservation& observation, bool allow_new_features) override;
  UncertainPose RobotPose() const override;
  void ResetRobotPose(const UncertainPose& pose) override;
  int Complexity() const override { return static_cast<int>(extents_.size()); }
  int Capacity() const override { return options_.capacity; }
  std::vector<MapLine> Lines() const override;
  std::string Serialize() const override;
  bool Deserialize(const std::string& bytes) override;

  // The update of Update() on lines already extracted, in the ROBOT frame.
  ScanUpdate UpdateWithLines(const std::vector<ObservedLine>& observed, bool allow_new_features);

  // Hooks for other measurement models on the same joint state (core/sonar uses them).
  // A batch EKF update with externally computed measurements: innovations `nu` (m), Jacobian
  // `h` (m x StateSize) over the full state, measurement covariance `r` (m x m). Returns false
  // (state unchanged) if the innovation covariance is not positive definite.
  bool UpdateWithMeasurements(const Eigen::VectorXd& nu, const Eigen::MatrixXd& h,
                              const Eigen::MatrixXd& r);
  // Adds a feature from a line observed in the ROBOT frame with covariance z.cov, independent of
  // the state, by the same inverse model as a laser feature (cross covariances with the robot
  // and the map). Returns its id, or -1 at capacity.
  int AddObservedFeature(const ObservedLine& z);
  // Adds a feature given jointly with the state: the map-frame line (rho, alpha), its
  // covariance `cov` and its cross covariance `cross` (2 x StateSize) with the state, and its
  // map-frame extent a-b (core/sonar: a line initialised from delayed vantage states). Returns
  // its id, or -1 at capacity or if `cross` has the wrong size.
  int AddJointFeature(const Vec2& line, const Mat2& cov, const Eigen::MatrixXd& cross,
                      const Vec2& a, const Vec2& b);
  // Grows the tracked extent of feature k to cover the map-frame points a and b.
  void GrowFeatureExtent(int k, const Vec2& a, const Vec2& b);

  // eq. 5 over the recent window, with the current robot covariance.
  double Quality() const;
  const RecentObservations& Recent() const { return recent_; }
  const LocalMapOptions& Options() const { return options_; }

  // Per observation of the last update: the id of the feature it was applied to, or -1.
  const std::vector<int>& LastAssociation() const { return last_association_; }
  // The lines of the last update (robot frame).
  const std::vector<ObservedLine>& LastObservations() const { return last_observations_; }
  // Whether the last update paired observations only in the recovery pass
  // (AssociationOptions::recovery_gate).
  bool LastUpdateRecovered() const { return last_recovered_; }

  // The full joint state and covariance; feature k occupies entries 3 + 2k, 4 + 2k (its rho may
  // be negative in the state: Lines() reports canonical lines).
  const Eigen::VectorXd& State() const { return x_; }
  const Eigen::MatrixXd& Covariance() const { return P_; }
  int FeatureId(int k) const { return ids_[k]; }
  // Index k of the feature with this id, or -1.
  int FeatureIndex(int id) const;

  // The odometry noise covariance Q(u) over (dx, dy, dtheta) used by Predict.
  static Mat3 OdometryNoise(const Pose2& u, const OdometryNoiseOptions& options);

  // Sets the robot pose to a solution computed from the features alone (bootstrap.h, eq. 12):
  // pose = f(lines, z), with d_lines = df/d(rho, alpha) of the features `feature_index` (2 per
  // feature, in that order) and pose_cov the part of its covariance due to the observations.
  // The robot-feature cross covariances become d_lines P_ll, keeping the map consistent.
  void SetRobotPoseFromFeatures(const Pose2& pose, const Mat3& observation_cov,
                                const std::vector<int>& feature_index,
                                const Eigen::Matrix<double, 3, Eigen::Dynamic>& d_lines);

 private:
  struct Extent {
    Vec2 a = Vec2::Zero();
    Vec2 b = Vec2::Zero();
  };
  Pose2 Robot() const { return Pose2{x_(0), x_(1), x_(2)}; }
  void AddFeature(const ObservedLine& z);
  void AppendFeature(const Vec2& line, const Mat2& cov, const Eigen::MatrixXd& cross, const Vec2& a,
                     const Vec2& b);
  // Q(u) of Predict: OdometryNoise without the calibration terms, plus the calibration errors
  // as errors that repeat every step since the last update that matched (their standard
  // deviation grows linearly with the distance and turn since then).
  Mat3 PredictNoise(const Pose2& u);
  void ClearCalibrationDrift();
  // Mahalanobis distance squared between an observation and the prediction of feature k.
  double SquaredDistanceTo(const ObservedLine& z, int k) const;
  void GrowExtent(int k, const ObservedLine& z);

  LocalMapOptions options_;
  Eigen::VectorXd x_;
  Eigen::MatrixXd P_;
  std::vector<int> ids_;
  std::vector<Extent> extents_;
  int next_id_ = 0;
  RecentObservations recent_;
  std::vector<int> last_association_;
  std::vector<ObservedLine> last_observations_;
  bool last_recovered_ = false;
  // Distances each wheel rolled and turn since the last corrected pose (not serialised).
  double calib_left_ = 0.0, calib_right_ = 0.0, calib_turn_ = 0.0;
};

}  // namespace atlas
