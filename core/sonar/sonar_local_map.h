#pragma once
// A line-feature local map that runs on laser alone, sonar alone, or both
// (SonarLocalMapOptions::sensors): the paper's laser and sonar experiments (Section IV,
// Fig. 8(a) and 8(b)) on one EKF.
//
// It wraps the laser path's LineEkfMap (same state, same Predict, same inverse model for new
// features) and adds the sonar path:
// - UpdateSonar(reading, ring, allow_new_features): each return with a usable range is paired
//   with the mapped line it can see (PredictSonarRange: normal inside the cone, tangent point
//   within the feature's extent plus max_extent_gap) when its squared Mahalanobis distance
//   passes the chi-square gate (1 dof) and no second feature is nearly as compatible; all
//   pairings are applied in one batch EKF update (LineEkfMap::UpdateWithMeasurements,
//   measurement z = range, h = d range / d(robot, line), R = range variance).
// - Returns compatible with no feature (at the loose gate) go to the SonarLineInitializer; if
//   the caller allows new features (mature hypotheses, Section III-E) and there is capacity,
//   its RANSAC + delayed-decision grouping may initialise lines, added with
//   LineEkfMap::AddJointFeature unless compatible with an existing feature (duplicate).
// - Delayed decision with consistent covariance: the vantage points the buffered returns were
//   fired from are delayed states of the EKF (delayed_vantages.h: their joint covariance with
//   the robot, the features and each other, updated with every Predict, sonar or laser update
//   and robot reset). An accepted line is refitted in the map frame over those vantage states
//   (range noise only) and added with its covariance, its cross covariance with the robot and
//   every feature through the vantage poses it was fitted from, and the vantage points'
//   cross covariance with it; the initialiser's RANSAC uses the vantage points' poses relative
//   to the robot with the covariance of that relative pose from the joint.
// - Specular misses: a return that is longer than a mapped wall echoing in its cone, or whose
//   whole cone crosses a mapped wall short of the range, came back after a second bounce
//   (multipath): it is neither used nor buffered, and buffered returns that a new feature shows
//   to be multipath are dropped. Edge-of-cone echoes are modelled (edge_incidence), not
//   rejected.
// - Update(scan) is the laser path (LineEkfMap::Update) when the laser is enabled; in
//   sonar-only mode it returns an empty ScanUpdate and changes nothing.
//
// How the Atlas calls it: per hypothesis, Predict(odometry) up to each sensor event's stamp,
// then Update(scan, mature) for a laser scan or UpdateSonar(reading, ring, mature) for a sonar
// reading (the ring is configuration: drivers/p2os P3dxSonarRing/B21SonarRing). For q (eq. 5)
// the SonarUpdate's (usable returns, matched) play the role of (||Z||, eta_a); Quality() does
// that over the recent window of whichever sensors are enabled.
//
// Serialize() stores the EKF (the LineEkfMap image) only: the initialiser's buffer of pending
// returns is a delay line and starts empty after Deserialize().

#include <memory>
#include <string>
#include <vector>

#include "core/localmap/line_ekf_map.h"
#include "core/localmap/quality.h"
#include "core/sonar/delayed_vantages.h"
#include "core/sonar/sonar_line_initializer.h"
#include "core/sonar/sonar_options.h"

namespace atlas {

// The pairing rule of a sonar return, shared by SonarLocalMap::UpdateSonar and the sonar w
// (sonar_map_bootstrapper.h). A line is a candidate when the return's tangent point `foot` lies
// within `max_extent_gap` of the line's observed extent (FootWithinExtent) and the return's
// innovation is inside the gate; of the candidates the nearest (Mahalanobis d2) is taken, unless
// the second nearest is within `ambiguity_margin` of it (NearestLine::Unambiguous).
bool FootWithinExtent(const MapLine& line, const Vec2& foot, double max_extent_gap);
class NearestLine {
 public:
  // Offers line k at d2 (inside the gate); true when k is now the nearest.
  bool Offer(int k, double d2);
  int best() const { return best_; }  // -1: none offered
  bool Unambiguous(double ambiguity_margin) const {
    return best_ >= 0 && (second_d2_ < 0.0 || second_d2_ - best_d2_ > ambiguity_margin);
  }

 private:
  int best_ = -1;
  double best_d2_ = 0.0, second_d2_ = -1.0;
};

// One return applied to a feature by UpdateSonar.
struct SonarPairing {
  int return_index = -1;    // into the reading's returns
  int feature = -1;         // feature index (state entries 3 + 2k, 4 + 2k)
  bool edge_echo = false;   // paired as an edge-of-cone echo (SonarRangePrediction)
  double innovation = 0.0;  // metres
};

struct SonarUpdate {
  int returns = 0;    // returns in the reading
  int usable = 0;     // with a range in [min_range, max_range_fraction * max_range)
  int matched = 0;    // applied to a feature
  int ambiguous = 0;  // compatible with two features alike: not used
  int behind = 0;     // longer than a mapped wall that echoes in the cone (multipath): dropped
  int buffered = 0;   // kept for initialisation
  int added = 0;      // features initialised
  GroupingOutcome grouping = GroupingOutcome::kInsufficient;
  std::vector<InitialisedLine> initialised;  // robot frame at this reading
  std::vector<SonarPairing> pairings;        // the returns applied (when matched > 0)
};

class SonarLocalMap final : public LocalMap {
 public:
  // `options` must be valid (Validate() empty).
  explicit SonarLocalMap(const SonarLocalMapOptions& options = SonarLocalMapOptions());

  std::unique_ptr<LocalMap> Clone() const override;
  void Predict(const Pose2& odometry_delta) override;
  void Predict(const Pose2& odometry_delta, const Mat3& covariance) override;
  ScanUpdate Update(const LaserScan& scan, bool allow_new_features) override;
  ScanUpdate Update(const ScanObservation& observation, bool allow_new_features) override;
  UncertainPose RobotPose() const override { return ekf_.RobotPose(); }
  void ResetRobotPose(const UncertainPose& pose) override;
  int Complexity() const override { return ekf_.Complexity(); }
  int Capacity() const override { return ekf_.Capacity(); }
  std::vector<MapLine> Lines() const override { return ekf_.Lines(); }
  std::string Serialize() const override;
  bool Deserialize(const std::string& bytes) override;

  // The sonar path (see above). Returns naming a transducer outside `ring` are skipped.
  SonarUpdate UpdateSonar(const SonarReading& reading, const std::vector<SonarTransducer>& ring,
                          bool allow_new_features);

  // The Atlas's sonar step (LocalMap::UpdateWithSonar): UpdateSonar with options.ring; for q
  // (eq. 5) the usable returns are the observations ||Z|| and the matched ones eta_a.
  ScanUpdate UpdateWithSonar(const SonarReading& reading, bool allow_new_features) override;

  // eq. 5 over the recent window of the enabled sensors.
  double Quality() const;

  // Sets the robot pose to one solved from the features alone (the sonar w of eq. 12,
  // sonar_map_bootstrapper.h): LineEkfMap::SetRobotPoseFromFeatures, which keeps the
  // robot-feature cross covariances. The returns buffered for initialisation and their vantage
  // states are dropped: they were fired before the robot left this frame, and their poses
  // relative to the robot now are unknown.
  void SetRobotPoseFromFeatures(const Pose2& pose, const Mat3& observation_cov,
                                const std::vector<int>& feature_index,
                                const Eigen::Matrix<double, 3, Eigen::Dynamic>& d_lines);

  const LineEkfMap& Ekf() const { return ekf_; }
  const SonarLineInitializer& Initializer() const { return init_; }
  const DelayedVantages& Vantages() const { return vantages_; }
  const SonarLocalMapOptions& Options() const { return o_; }

 private:
  // The laser path of both Update overloads (a LaserScan or a ScanObservation, given to ekf_).
  template <typename Laser>
  ScanUpdate UpdateWithLaser(const Laser& laser, bool allow_new_features);
  // Predict with the given covariance, or the odometry noise model when null.
  void PredictWith(const Pose2& u, const Mat3* covariance);
  bool Duplicate(const ObservedLine& z) const;
  // True when the cone of a return fired from `sensor` (map frame) is blocked by a mapped wall
  // nearer than the range (central and both edge rays meet a feature's extent at least
  // behind_sigmas range sigmas short of it): the echo came back after a second bounce.
  bool ThroughWall(const Pose2& sensor, double half_cone, double range) const;

  SonarLocalMapOptions o_;
  LineEkfMap ekf_;
  SonarLineInitializer init_;
  // Keeps the vantage points that buffered returns refer to as delayed states (adds new ones,
  // marginalises unused ones).
  void SyncVantages();
  // Gives the initialiser every vantage point's relative pose and covariance from the joint.
  void RefreshVantages();
  DelayedVantages vantages_;
  RecentObservations sonar_recent_;
};

}  // namespace atlas
