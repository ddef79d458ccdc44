#pragma once
// The sonar initialiser's vantage points as delayed states of the local map's EKF (delayed
// decision making, Leonard and Rikoski; paper Section IV, Fig. 9): a line initialised from
// returns fired at past robot poses depends on those poses, which are correlated with the
// current robot pose and with every feature. Each vantage point in use is kept as an extra
// state of three rows, the map-frame robot pose at firing, with its joint covariance with the
// EKF state s (robot pose, lines) and with the other vantage points:
//
//   augmented state (s, v_1 .. v_m),  covariance [[P, C^T], [C, V]],  C = Cov(v, s) (3m x n).
//
// A vantage point enters as a copy of the robot rows (Augment: v = x_r, C_v = P_r., V_vv = P_rr)
// and is marginalised (its rows dropped: Keep) once no buffered return refers to it; at most
// SonarInitOptions::max_vantage of them (bounded work). The EKF's operations are mirrored:
// - Predict: x_r <- x_r (+) u with F = d(x_r (+) u)/dx_r: C's robot columns <- C_r F^T.
// - Update: a batch update of the EKF (z = H s + noise R): with S = H P H^T + R and
//   K_v = C H^T S^-1, v <- v + K_v nu, C <- C - K_v H P, V <- V - K_v H C^T (exact, the
//   sonar updates). Follow: an update the caller did not form (the laser path's): for any
//   linear update P' = (I - K H) P, and C in the range of P, C' = C P^+ P', v' = v + C P^+ (s'
//   - s), V' = V - C P^+ (P - P') P^+ C^T; features added by the inverse model in the same call
//   (s' longer than s) get their cross covariances from the same formula.
// - A feature initialised from the vantage points (AppendFeature): its cross covariance with
//   the vantage points is appended as two columns of C.
// - ResetRobotPose (traversal into a frame, Section III-D): the robot is placed with a new
//   pose independent of the features; the vantage points keep their poses relative to the
//   robot, with that relative pose's joint covariance (Reanchor).
// Relative(): a vantage point's pose in the current robot frame and its covariance (from the
// joint of robot and vantage point), what the initialiser's RANSAC works with.

#include <Eigen/Core>
#include <cstdint>
#include <vector>

#include "core/geometry/se2.h"

namespace atlas {

class DelayedVantages {
 public:
  int Size() const { return static_cast<int>(ids_.size()); }
  void Clear();
  // Index of the vantage point `id`, or -1.
  int IndexOf(int64_t id) const;
  int64_t Id(int i) const { return ids_[i]; }
  // Map-frame pose of vantage point i.
  Pose2 Pose(int i) const { return Pose2{v_(3 * i), v_(3 * i + 1), v_(3 * i + 2)}; }
  const Eigen::MatrixXd& CrossCovariance() const { return c_; }  // C, 3m x n
  const Eigen::MatrixXd& Covariance() const { return vv_; }      // V, 3m x 3m

  // Adds the robot pose (entries 0-2 of the EKF state x, covariance p) as vantage point `id`.
  void Augment(int64_t id, const Eigen::VectorXd& x, const Eigen::MatrixXd& p);
  // Marginalises every vantage point whose id is not in `ids`.
  void Keep(const std::vector<int64_t>& ids);
  void Predict(const Mat3& f);
  // Mirrors the EKF update (nu, h, r) about to be applied to covariance p (see above).
  void Update(const Eigen::VectorXd& nu, const Eigen::MatrixXd& h, const Eigen::MatrixXd& r,
              const Eigen::MatrixXd& p);
  // Mirrors an EKF change from (x0, p0) to (x1, p1) by a linear update and inverse-model
  // additions (see above). Angles: entry 2 and every 4 + 2k are wrapped.
  void Follow(const Eigen::VectorXd& x0, const Eigen::MatrixXd& p0, const Eigen::VectorXd& x1,
              const Eigen::MatrixXd& p1);
  // Appends a new EKF state pair whose cross covariance with the vantage points is `cov_v`
  // (3m x 2).
  void AppendFeature(const Eigen::MatrixXd& cov_v);
  // The robot pose was `robot` with EKF covariance p (n x n); it is reset to `pose` (covariance
  // pose_cov, no cross covariance with the features).
  void Reanchor(const Pose2& robot, const Eigen::MatrixXd& p, const Pose2& pose,
                const Mat3& pose_cov);
  // Vantage point i in the frame of the robot at `robot` (EKF covariance p): pose and covariance.
  void Relative(int i, const Pose2& robot, const Eigen::MatrixXd& p, Pose2& pose, Mat3& cov) const;

 private:
  std::vector<int64_t> ids_;
  Eigen::VectorXd v_;
  Eigen::MatrixXd c_;
  Eigen::MatrixXd vv_;
};

}  // namespace atlas
