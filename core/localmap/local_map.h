#pragma once
// The local map of one map-frame, as the Atlas framework drives it (paper, Sections II-III).
//
// The framework needs only this interface; the feature-based EKF of lines is one
// implementation (Condition 1: it must produce a consistent map). Other representations
// (occupancy grids, particle filters) may be added behind the same interface.
//
// Contract:
// - Every quantity is in the coordinates of the map-frame that owns the map.
// - Predict() then Update() per scan (or UpdateWithSonar() per sonar reading); the caller
//   integrates odometry up to the measurement's stamp. Update(ScanObservation) is Update(scan)
//   with the scan's lines shared by every map the observation is given to (scan_observation.h).
// - A juvenile hypothesis calls Update() with allow_new_features = false (Section III-E).
// - New features are added only while Complexity() < Capacity() (Section I-A, map capacity).
// - No I/O, no exceptions; data-dependent outcomes are typed results.

#include <algorithm>
#include <memory>
#include <string>
#include <vector>

#include "core/common/sensor_types.h"
#include "core/geometry/se2.h"
#include "core/localmap/scan_observation.h"

namespace atlas {

// An infinite line rho = x cos(alpha) + y sin(alpha) with alpha in (-pi, pi], rho >= 0, its
// 2x2 covariance over (rho, alpha), and the observed extent as two endpoints on the line.
struct MapLine {
  int id = -1;  // unique within its map
  double rho = 0.0;
  double alpha = 0.0;
  Eigen::Matrix2d cov = Eigen::Matrix2d::Zero();
  Vec2 endpoint_a = Vec2::Zero();
  Vec2 endpoint_b = Vec2::Zero();
};

// What one scan update did: the inputs of the quality metric q, eq. 5.
struct ScanUpdate {
  int observations = 0;  // ||Z||: features extracted from the scan
  int matched = 0;       // eta_a: observations associated to map features
  int added = 0;         // new features initialised
  bool ambiguous = false;
};

class LocalMap {
 public:
  virtual ~LocalMap() = default;

  virtual std::unique_ptr<LocalMap> Clone() const = 0;

  // Moves the robot by an odometry increment expressed in the robot frame at the previous
  // pose (the difference of two odometry samples, Between(prev, cur)). Covariance grows with
  // distance and turn.
  virtual void Predict(const Pose2& odometry_delta) = 0;
  // The same with the increment's covariance given (over dx, dy, dtheta in the robot frame at
  // the previous pose) instead of the map's odometry noise model: for increments measured by
  // other means, e.g. scan matching (core/scanmatch/scan_matcher.h).
  virtual void Predict(const Pose2& odometry_delta, const Mat3& covariance) = 0;

  // Updates the map and pose with a laser scan taken at the current (predicted) pose.
  virtual ScanUpdate Update(const LaserScan& scan, bool allow_new_features) = 0;
  // The same update from an observation of the scan: maps that extract lines take them from
  // `observation` (extracted once for all maps given it) and give the result of
  // Update(observation.scan(), ...) exactly. Default: Update(observation.scan(), ...).
  // A map overriding only one of the two declares `using LocalMap::Update;`.
  virtual ScanUpdate Update(const ScanObservation& observation, bool allow_new_features) {
    return Update(observation.scan(), allow_new_features);
  }

  // Updates with one sonar ring reading taken at the current (predicted) pose. For q (eq. 5)
  // the result's `observations` are the usable returns and `matched` those applied to a
  // feature. Maps without a sonar path ignore the reading (an empty ScanUpdate: no evidence
  // either way), which is the default.
  virtual ScanUpdate UpdateWithSonar(const SonarReading& reading, bool allow_new_features) {
    (void)reading;
    (void)allow_new_features;
    return ScanUpdate{};
  }

  // The robot pose and its 3x3 marginal covariance in this map-frame.
  virtual UncertainPose RobotPose() const = 0;
  // Replaces the robot pose (and clears its correlation with the features): used to seed a
  // juvenile hypothesis (eq. 10-11) and by Genesis (pose exactly zero, covariance zero).
  virtual void ResetRobotPose(const UncertainPose& pose) = 0;

  // Map complexity (feature count) and the capacity it may not exceed.
  virtual int Complexity() const = 0;
  virtual int Capacity() const = 0;

  // Read access to the features with their marginal covariances.
  virtual std::vector<MapLine> Lines() const = 0;
  // What the map holds as points (map-frame), at most `max_points`, for pictures of the map
  // (the export's points.tsv, formats/replay_dir.h). Default: none (a map of lines is drawn by
  // its Lines()).
  virtual std::vector<Vec2> Points(int max_points) const {
    (void)max_points;
    return {};
  }

  // Whether `point` (map-frame) lies within `reach` metres of what the map holds, so that a
  // robot there could see it (traversal, Section III-E). Default: of one of Lines()' segments.
  virtual bool Reaches(const Vec2& point, double reach) const {
    for (const MapLine& l : Lines()) {
      const Vec2 d = l.endpoint_b - l.endpoint_a;
      const double len2 = d.squaredNorm();
      const double t = len2 > 0 ? std::clamp((point - l.endpoint_a).dot(d) / len2, 0.0, 1.0) : 0.0;
      if ((l.endpoint_a + t * d - point).norm() <= reach) return true;
    }
    return false;
  }

  // A self-contained byte image of the map, and its inverse. Deserialize returns false (and
  // leaves the map unchanged) on bytes that are not a valid image.
  virtual std::string Serialize() const = 0;
  virtual bool Deserialize(const std::string& bytes) = 0;
};

}  // namespace atlas
