#pragma once
// Feature initialisation from several vantage points (paper, Section IV, Fig. 9): RANSAC
// grouping of buffered sonar returns with delayed decision making (Leonard and Rikoski).
//
// Buffer: returns that no mapped feature explains are kept with the vantage point they were
// fired from. A vantage point is the robot pose at firing expressed in the CURRENT robot
// frame, with the covariance of that relative pose accumulated from the odometry noise of
// every Predict since (V <- (-)u (+) V, eq. 2 with J(-) as in eq. 15). Everything is relative to
// the robot, so ResetRobotPose/Genesis/traversal do not disturb the buffer. Bounded: at most
// max_returns returns and max_vantage vantage points, none farther than window_m away.
//
// Decide(): up to `iterations` RANSAC hypotheses. Each draws two returns from vantage points at
// least min_pair_baseline apart and takes the (at most two) lines tangent to both arcs with the
// normal inside both cones (CommonTangentLines). Its consensus is the set of returns whose range
// matches the distance to the line within inlier_sigmas (range noise plus the vantage pose's
// uncertainty) with the line echoing (in the cone; edge echoes too only when
// SonarInitOptions::edge_echoes). The best consensus is refined
// by Gauss-Newton (weighted least squares over (rho, alpha) in the robot frame) and accepted only
// when the decision is clear:
//   - support >= min_support returns from >= min_vantage vantage points spanning >= min_baseline;
//   - the tangent points span >= min_extent_ratio of that baseline (arcs through one corner or
//     edge are tangent to many lines: a point reflector, not a wall);
//   - no point rival (SonarInitOptions::point_rival): one point reflector, fitted to the
//     inliers' ranges, does not explain rival_ratio of them (a head-on wall and a corner give
//     the same ranges: the decision waits until the vantage points tell them apart);
//   - no rival: no other hypothesis with a clearly different line claims rival_overlap of the
//     same returns with rival_ratio of the support (else kAmbiguous: wait for more returns).
// An accepted line leaves the buffer with its inliers and is returned in the ROBOT frame with
// covariance (H^T W H)^-1 plus floors, with the ids and transducers of its supporting returns.
//
// Used alone, the vantage points' relative poses come from the odometry (Predict) and are
// treated as independent of each other and of any map. SonarLocalMap keeps the vantage points
// as delayed states of its EKF (delayed_vantages.h), gives the initialiser their relative poses
// from that joint (SetVantage), and adds an accepted line refitted over the joint, with the
// correlation with the past poses (the consistent covariance of delayed decision making). The
// RANSAC inlier test and the robot-frame refinement here still treat the vantage points as
// independent of each other (a grouping decision, not the line's covariance in the map).

#include <Eigen/Core>
#include <cstdint>
#include <random>
#include <utility>
#include <vector>

#include "core/common/sensor_types.h"
#include "core/localmap/line_model.h"
#include "core/sonar/sonar_options.h"

namespace atlas {

enum class GroupingOutcome { kAccepted, kAmbiguous, kInsufficient };

struct SonarVantage {
  Pose2 pose;  // robot pose at firing, in the current robot frame
  Mat3 cov = Mat3::Zero();
  int64_t id = 0;  // unique within this initialiser (DelayedVantages keys)
};

struct BufferedReturn {
  int vantage = 0;        // index into Vantages()
  SonarTransducer mount;  // beam width already scaled by cone_scale
  double range = 0.0;
};

struct InitialisedLine {
  ObservedLine line;                    // robot frame, canonical, covariance over (rho, alpha)
  std::vector<Pose2> vantage;           // robot-frame vantage points of the supporting returns
  std::vector<Vec2> tangent_points;     // robot frame
  std::vector<Pose2> sensors;           // robot-frame transducer poses of the supporting returns
  std::vector<double> ranges;           // their ranges
  std::vector<SonarTransducer> mounts;  // their transducers (beam width scaled by cone_scale)
  std::vector<int64_t> vantage_ids;     // SonarVantage::id of each supporting return
  int support = 0;
  double baseline = 0.0;
};

struct GroupingDecision {
  GroupingOutcome outcome = GroupingOutcome::kInsufficient;
  std::vector<InitialisedLine> lines;  // accepted this call (may be non-empty with kAmbiguous)
  int hypotheses = 0;                  // RANSAC hypotheses scored
};

class SonarLineInitializer {
 public:
  SonarLineInitializer(const SonarInitOptions& init, const SonarModelOptions& model);

  // The robot moved by u (robot frame) with odometry noise covariance q over u.
  void Predict(const Pose2& u, const Mat3& q);
  // Buffers one return fired now (from the current robot pose) by the transducer `mount`.
  void Add(const SonarTransducer& mount, double range);
  // One decision (see above); accepted lines are removed from the buffer.
  GroupingDecision Decide();
  void Clear();
  // Drops the buffered returns for which drop(sensor pose in the current robot frame, mount,
  // range) is true (e.g. returns that a newly mapped wall shows to be multipath).
  template <typename Pred>
  void DropReturnsIf(Pred drop) {
    std::erase_if(returns_, [&](const BufferedReturn& r) {
      return drop(Compose(vantage_[r.vantage].pose, r.mount.pose), r.mount, r.range);
    });
  }

  const std::vector<SonarVantage>& Vantages() const { return vantage_; }
  // Replaces vantage point i's relative pose and covariance (SonarLocalMap: from the delayed
  // states, DelayedVantages::Relative).
  void SetVantage(int i, const Pose2& pose, const Mat3& cov) {
    vantage_[i].pose = pose;
    vantage_[i].cov = cov;
  }
  // Ids of the vantage points that buffered returns refer to.
  std::vector<int64_t> VantagesInUse() const;
  // The effective model (edge_incidence 0 unless SonarInitOptions::edge_echoes).
  const SonarModelOptions& Model() const { return m_; }
  const std::vector<BufferedReturn>& Returns() const { return returns_; }
  // Variance of return j's range about the line (rho, alpha) (robot frame), incl. its pose.
  double ReturnVariance(const BufferedReturn& r, double rho, double alpha) const;

 private:
  void DropOld();
  int CountInliers(const Vec2& line, std::vector<char>& mask) const;
  bool Refine(Vec2& line, const std::vector<char>& mask, Mat2& cov) const;
  // How many of the returns in `mask` one point reflector, fitted to them from `start`,
  // explains (in its transducer's cone, range within inlier_sigmas).
  int PointSupport(const std::vector<char>& mask, Vec2 start) const;
  // Variance of return r's range: its noise, model_sigma, and its vantage pose's covariance
  // through d_vantage = d range / d vantage pose.
  double RangeVariance(const BufferedReturn& r, const Eigen::RowVector3d& d_vantage) const;

  SonarInitOptions o_;
  SonarModelOptions m_;
  std::vector<SonarVantage> vantage_;
  std::vector<BufferedReturn> returns_;
  bool moved_since_vantage_ = true;
  int64_t next_vantage_id_ = 0;
  std::mt19937_64 rng_;
};

}  // namespace atlas
