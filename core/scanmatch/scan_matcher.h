#pragma once
// Scan-to-scan matching: the robot's motion between two consecutive laser scans, estimated from
// the scans with the wheel odometry's increment as a Gaussian prior. No I/O.
//
// Why (our addition; the paper's local maps take odometry as given, Section II): the atlas is
// only as good as its local maps (Condition 1), and a line EKF associates its observations by
// gating around the predicted pose. With the B21 of mit-csail the wheels turn 6-19 deg wrong
// within 0.4 s; the 99 % gate then admits walls 20-40 deg off, lone wrong pairings turn the
// heading, and every Genesis edge made afterwards inherits the error (docs/design.md, "Scan
// matching"). The scans themselves fix the heading change between consecutive scans to a fraction
// of a degree wherever two non-parallel surfaces are in view. The result replaces the odometry
// increment and its covariance Q(u) in the maps' Predict (LocalMap::Predict(u, Q)).
//
// Method: point-to-line ICP (Censi's PL-ICP without the closed form), maximum a posteriori:
//   x* = argmin  sum_i rho(n_i . (x (+) q_i - p_i)) / sigma^2  +  (x - u)^T Q^-1 (x - u)
// with q_i the current scan's points (robot frame), p_i and n_i the reference scan's nearest
// point and its surface normal (local fit over neighbouring beams), found by projecting x (+) q_i
// into the reference scan's beam index (bounded: `search_beams` either side), rho a Huber
// kernel, u the odometry increment with covariance Q (the prior). Optionally (`heading_search`,
// off by default: on mit-csail it cost 50 % more time and gained nothing, docs/design.md,
// "Scan matching") a bounded search over the heading (either side of u in `heading_step` steps)
// first picks the start with the most point pairs within `coarse_distance`.
//
// Covariance: C = (J^T W J / (sigma^2 s) + Q^-1)^-1 at the solution, s = `information_scale`^-1.
// The Hessian of ICP is known to be over-confident (Censi 2007: the pairing and the normals'
// errors are not in it), so its information is scaled down; directions the scans do not fix (a
// corridor's axis) keep the odometry's covariance through the prior term.
//
// Use of the same scan twice: the EKF then updates with lines from the scan that also made the
// increment. The correlation is ignored (as in every laser-odometry front end); the information
// scale keeps the increment's share small.
//
// Recovery (`recovery_heading_search`): when the match at the odometry's increment fails, a
// wider heading search and a weak prior give the scans a second chance (see the option).
//
// Outcomes are typed (ScanMatchOutcome); anything but kMatched means: use the odometry prior.
// Work per call is bounded: at most `max_iterations` passes of O(points x (2 search_beams + 1)).
// Errors: never throws; options must be valid (Validate()).

#include <string>
#include <vector>

#include "core/common/sensor_types.h"
#include "core/geometry/se2.h"

namespace atlas {

// The most beams either side a reference point's normal is fitted over.
inline constexpr int kMaxNormalBeams = 32;

struct ScanMatchOptions {
  bool enabled = true;        // the StepLoop matches consecutive laser scans (scan_match.enabled)
  double min_range = 0.1;     // metres; shorter returns are not used
  double max_range = 20.0;    // metres; longer returns are not used
  double point_sigma = 0.03;  // metres, point-to-line residual noise
  double information_scale = 0.3;  // the ICP Hessian's information is multiplied by this
  double huber_k = 2.0;            // Huber threshold in point_sigma
  // A reference point's normal: a fit over the neighbours within `normal_radius` among
  // `normal_beams` beams either side, used only if flat (rms across under `max_normal_rms`)
  // and long (rms along at least `min_normal_extent`: a fit over a few centimetres of densely
  // sampled near wall has a noisy normal that would observe the motion along that wall).
  int normal_beams = 8;
  double normal_radius = 0.3;       // metres
  double max_normal_rms = 0.02;     // metres
  double min_normal_extent = 0.03;  // metres
  // Current points closer than this to the previous point kept are skipped, so that the dense
  // near walls do not outweigh the rest of the scan.
  double min_point_spacing = 0.05;  // metres
  int search_beams = 8;             // reference beams searched either side of the projection
  double max_distance = 0.3;        // metres, pairs farther apart are not used (first passes)
  double final_distance = 0.1;      // metres, after `coarse_iterations`
  int coarse_iterations = 4;
  int max_iterations = 20;
  double heading_search = 0.0;  // radians either side of the odometry's heading (0: none)
  // Recovery: when the match at the odometry's increment fails (too few pairs, no
  // convergence), a second match starts from the best of a heading search this wide (radians
  // either side; 0: none) with the odometry as a weak prior (sigma `recovery_sigma_xy` in x
  // and y, the search width in heading). On mit-csail the odometry sometimes stands still for
  // 0.6 s while the robot turns, then reports 45-degree steps: its increments (and their
  // covariance, zero for zero motion) are then not a prior worth keeping. Off by default: on
  // mit-csail it recovered 30-50 such steps per run and made the short relations better at 7
  // of 8 laser time offsets, but the atlas's median over the offsets worse (docs/design.md,
  // "Scan matching").
  double recovery_heading_search = 0.0;
  double recovery_sigma_xy = 0.3;  // metres
  double heading_step = 0.0175;    // radians
  double coarse_distance = 0.15;   // metres, a pair counted by the heading search
  int min_pairs = 40;              // pairs needed at the solution
  double min_pair_fraction = 0.3;  // of the current scan's usable points
  std::string Validate() const;    // empty when valid
  bool operator==(const ScanMatchOptions&) const = default;
};

enum class ScanMatchOutcome {
  kMatched,
  kTooFewPoints,  // a scan has fewer usable points than min_pairs
  kTooFewPairs,   // the solution pairs too few points (new view, open space)
  kNotConverged,  // max_iterations without the step becoming small
};
const char* ToString(ScanMatchOutcome o);

struct ScanMatchResult {
  ScanMatchOutcome outcome = ScanMatchOutcome::kTooFewPoints;
  // The pose of the robot at the current scan in the robot frame at the reference scan, and
  // its covariance; the prior when outcome != kMatched.
  UncertainPose increment;
  int pairs = 0;     // point pairs at the solution
  int points = 0;    // usable points of the current scan
  double rms = 0.0;  // metres, rms point-to-line residual of the pairs
  int iterations = 0;
  bool recovered = false;  // matched by the recovery pass (weak prior)
};

// cos and sin of each beam's bearing (angle_min + i * angle_increment, in double) of a scan
// layout, kept until a scan of another layout: a scanner's scans share one layout, and the
// matcher turns every scan into points twice (as the current scan, then as the reference).
class BeamDirections {
 public:
  // The directions of `scan`'s beams (one per range); valid until the next call.
  const std::vector<Vec2>& Of(const LaserScan& scan);

 private:
  float angle_min_ = 0.0f;
  float angle_increment_ = 0.0f;
  std::vector<Vec2> directions_;
};

// A reference scan prepared for matching (its points and normals); reused for many queries.
class ScanMatcher {
 public:
  explicit ScanMatcher(const ScanMatchOptions& options);

  // Makes `scan` the reference for later Match calls.
  void SetReference(const LaserScan& scan);
  bool HasReference() const { return has_reference_; }
  void ClearReference() { has_reference_ = false; }

  // The motion from the reference scan to `scan`, with `prior` the odometry increment.
  ScanMatchResult Match(const LaserScan& scan, const UncertainPose& prior);

  const ScanMatchOptions& options() const { return options_; }

 private:
  struct RefPoint {
    Vec2 p = Vec2::Zero();
    Vec2 n = Vec2::Zero();
    bool has_normal = false;
    bool valid = false;
  };
  // The reference point nearest to w (reference robot frame) among the beams around its
  // projection, or null.
  const RefPoint* Nearest(const Vec2& w, double max_distance) const;
  int CountPairs(const Pose2& x, const std::vector<Vec2>& points, double max_distance) const;
  // The heading within `half_width` of u's (u's position) that pairs the most points.
  Pose2 SearchHeading(const Pose2& u, double half_width) const;
  // Iterates from `start` under `prior`; fills out's outcome, increment, pairs, rms, iterations.
  void Solve(const Pose2& start, const UncertainPose& prior, ScanMatchResult* out) const;

  ScanMatchOptions options_;
  bool has_reference_ = false;
  std::vector<RefPoint> ref_;  // one per beam of the reference
  // ref_[i].p where ref_[i].has_normal, else infinite (never nearest): what Nearest scans.
  std::vector<Vec2> with_normal_;
  // The reference robot frame -> the reference sensor frame.
  RigidTransform ref_sensor_inverse_{Pose2{}};
  double ref_angle_min_ = 0.0;
  double ref_increment_ = 0.0;
  std::vector<Vec2> points_;  // scratch: current scan's points
  BeamDirections directions_;
};

// The usable returns of a scan as points in the robot frame, in beam order (no-return and out
// of [min_range, max_range] beams skipped); `directions` = BeamDirections::Of(scan).
void ScanPointsInRobotFrame(const LaserScan& scan, const std::vector<Vec2>& directions,
                            double min_range, double max_range, std::vector<Vec2>* points);

}  // namespace atlas
