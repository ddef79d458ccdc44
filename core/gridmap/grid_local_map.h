#pragma once
// A dense local map: the map-frame holds a bounded probability grid of its laser evidence
// (Hess et al. 2016, Section IV-B, "Submaps"; 5 cm cells, hit/miss with ray casting,
// core/grid/range_inserter.h) and the robot pose in the frame, behind the LocalMap interface
// the Atlas framework drives (paper, Sections II-III; docs/design.md, "Dense frames").
//
// - Predict(u): x <- x (+) u; the robot's covariance relative to the grid grows by the odometry
//   noise Q(u) (LineEkfMap::OdometryNoise, the line map's model) or the given increment noise.
// - Update(scan): the scan's returns (robot frame, at most match_max_range) are aligned to the
//   grid from the predicted pose (ScanAligner: correlative search, then least squares on the
//   bicubic grid; covariance from the match's Hessian, over information_scale). The aligned
//   pose is a measurement of the robot relative to the grid, fused with the prediction by a
//   Kalman update; a direction the grid does not fix (a corridor's length) has a huge variance
//   in the measurement, so that axis keeps the odometry with its noise. A measurement outside
//   `gate_chi2` of the prediction, a low score or too few points leaves the prediction.
// - Condition 1: the grid's cells carry the error of the poses they were inserted at. The
//   marginal robot covariance in the frame is the covariance relative to the grid plus that of
//   the grid near the robot: the smallest (trace) covariance of a scan inserted within
//   grid_cov_radius of the robot (the cells it sees were placed at least that well), else that
//   of the nearest inserted scan. A robot matched 8 m from the origin is thus not claimed to be
//   known to a centimetre in the frame, and one back where the frame began is.
// - ScanUpdate for q (eq. 5): observations are the matched points, `matched` those that fall on
//   (or next to) an occupied cell at the updated pose.
// - Bounds (Section I-A): a mature hypothesis inserts a scan when it moved insert_min_distance
//   or turned insert_min_angle since the last insertion, at most max_scans scans, and only
//   while the robot is within max_extent of the frame's origin; past it the map is full.
//   Complexity() counts the scans inserted (Capacity() when full), so that Genesis at capacity
//   (III-C) starts a new frame when the robot leaves what the grid explains.
// - Lines() is empty: nothing in this map needs straight walls. Reaches() tells traversal
//   whether a seed lies within reach of the poses the grid was made from. Points() are the
//   centres of the occupied cells (probability >= kOccupiedProbability), evenly subsampled
//   over the cells in row order when there are more than asked for.
//
// Not thread-safe; copyable (Clone) and serialisable (versioned binary image).

#include <cstdint>
#include <memory>
#include <string>
#include <utility>
#include <vector>

#include "core/grid/grid_options.h"
#include "core/grid/probability_grid.h"
#include "core/grid/range_inserter.h"
#include "core/grid/scan_alignment.h"
#include "core/localmap/local_map.h"
#include "core/localmap/localmap_options.h"

namespace atlas {

// A cell of probability at least this is occupied (Points(); grid_map_matcher.h).
inline constexpr double kOccupiedProbability = 0.6;

// A search for points in a frame's grid (dense_search.h): w of eq. 12
// (grid_map_bootstrapper.h) and map-matching (grid_map_matcher.h) each have one.
struct GridSearchOptions {
  double min_linear_window = 0.3;   // metres either side, at least (3 sigma of the prior)
  double max_linear_window = 2.0;   // metres either side, at most
  double min_angular_window = 0.1;  // radians either side, at least
  double max_angular_window = 0.35;
  int max_points = 600;  // points searched for (evenly subsampled)
  // Only the points within this many metres of the robot are searched for (SearchPoints): the
  // search's heading step is a cell at the farthest point, so far points multiply its work, and
  // their heading error is the largest (docs/design.md, "Dense frames").
  double max_point_range = 8.0;
  int64_t max_nodes = 400000;  // branch-and-bound work bound
  // A search spread over steps (map-matching, w) does at most about this many cell visits per
  // step (DenseSearch::Continue): precomputed cells, and points scored at each node. The
  // default does not slice: sliced at 700000 (about 2 ms) the steps keep the 10 ms budget, but
  // the returns are less accurate and loop closures are sometimes false (docs/design.md,
  // "Constant time").
  int64_t work_per_step = int64_t{1} << 40;
  double min_score = 0.4;    // mean cell probability of the best placement
  double min_margin = 0.05;  // best minus runner-up outside its peak (Condition 2)
  // When the prior's 3 sigma exceeds max_linear_window, the best placement's heading is searched
  // for a rival this far either side of the prior (metres; at most the prior's 3 sigma). It
  // bounds that search's work; at most max_linear_window switches it off.
  double max_repetition_window = 8.0;
  // Floors of the placement's standard deviations (at least GridLocalMapOptions::min_sigma_*).
  double min_sigma_xy = 0.0;     // metres
  double min_sigma_theta = 0.0;  // radians
  std::string Validate() const;
};

struct GridLocalMapOptions {
  // core/grid's defaults, but returns at grazing incidence (below 20 degrees) are not used, and
  // one hit or miss counts more (0.7, 0.4 instead of 0.55, 0.49): a frame holds tens of scans,
  // not the hundreds of a Cartographer submap, and with 0.55 a wall seen once scores barely
  // above the free space in front of it, so a scan slides off it towards the robot.
  GridOptions grid = [] {
    GridOptions g;
    g.range.min_incidence = 0.35;
    g.grid.max_cells = 512;  // 25.6 m: a frame's extent and the laser's reach indoors
    g.grid.hit_probability = 0.7;
    g.grid.miss_probability = 0.4;
    return g;
  }();
  // Work bounds: a search of max_points points over max_nodes nodes takes a few milliseconds.
  GridSearchOptions bootstrap = [] {
    GridSearchOptions w;
    w.max_points = 300;
    w.max_nodes = 60000;
    return w;
  }();
  GridSearchOptions match = [] {
    GridSearchOptions m;
    m.min_linear_window = 0.5;
    m.max_linear_window = 3.0;
    m.max_angular_window = 0.5;
    m.max_points = 250;
    m.max_nodes = 40000;
    m.min_margin = 0.08;
    m.min_sigma_xy = 0.1;
    m.min_sigma_theta = 0.03;
    return m;
  }();
  // Map-matching's free-space test (grid_map_matcher.h, Condition 2): the largest fraction of
  // either frame's occupied cells near the robot that may fall in the other frame's observed
  // free space at the placement found; 1 never refuses.
  double max_free_space_conflict = 0.05;
  OdometryNoiseOptions odometry;
  int max_scans = 40;                // scans a frame's grid holds (its capacity)
  double max_extent = 6.0;           // metres from the frame's origin where scans are inserted
  double insert_min_distance = 0.2;  // metres moved since the last inserted scan
  double insert_min_angle = 0.17;    // radians turned since the last inserted scan
  double match_max_range = 25.0;     // returns beyond are not aligned (half the grid's side)
  int max_points = 250;              // returns aligned per scan (evenly subsampled)
  // The match's information (H / s^2) is multiplied by this: the Hessian of a grid match is
  // over-confident (Censi 2007), as the scan matcher's is (docs/design.md, "Scan matching").
  double information_scale = 0.3;
  double min_sigma_xy = 0.01;      // metres: floor added to the measurement's variance
  double min_sigma_theta = 0.005;  // radians
  double gate_chi2 = 16.27;        // 3 dof, 99.9 %: innovation gate of the measurement
  double grid_cov_radius = 2.0;    // metres (Condition 1 above)
  std::string Validate() const;    // empty when valid
};

class GridLocalMap final : public LocalMap {
 public:
  // `options` must be valid. The robot starts at the origin with zero covariance (Genesis).
  explicit GridLocalMap(const GridLocalMapOptions& options = GridLocalMapOptions());

  std::unique_ptr<LocalMap> Clone() const override;
  void Predict(const Pose2& odometry_delta) override;
  void Predict(const Pose2& odometry_delta, const Mat3& covariance) override;
  using LocalMap::Update;
  ScanUpdate Update(const LaserScan& scan, bool allow_new_features) override;
  UncertainPose RobotPose() const override;
  void ResetRobotPose(const UncertainPose& pose) override;
  int Complexity() const override;
  int Capacity() const override { return options_.max_scans; }
  std::vector<MapLine> Lines() const override { return {}; }
  bool Reaches(const Vec2& point, double reach) const override;
  std::vector<Vec2> Points(int max_points) const override;
  std::string Serialize() const override;
  bool Deserialize(const std::string& bytes) override;

  const ProbabilityGrid& Grid() const { return grid_; }
  const GridLocalMapOptions& Options() const { return options_; }
  // The alignment of the last Update (outcome kTooFewPoints when none was tried).
  const AlignmentResult& LastAlignment() const { return last_alignment_; }
  // Whether the last Update's measurement was used (aligned and inside the gate).
  bool LastUpdateMatched() const { return last_matched_; }
  // The last Update's scan as aligned (AlignmentPoints, robot frame; not serialised).
  const std::vector<Vec2>& LastScanPoints() const { return last_points_; }
  // The robot frame's returns of `scan` used for alignment (subsampled), as Update takes them.
  std::vector<Vec2> AlignmentPoints(const LaserScan& scan) const;
  // Points of `points` (robot frame) that fall on or next to an occupied cell from `robot`.
  int ExplainedPoints(const std::vector<Vec2>& points, const Pose2& robot) const;
  // The covariance of the grid's cells near `p` (frame): Condition 1 above.
  Mat3 GridCovarianceNear(const Vec2& p) const;
  // Changes whenever the grid does (an id per map lineage and the scans inserted), for caches
  // of what is computed from the grid.
  std::pair<uint64_t, int> Revision() const {
    return {id_, static_cast<int>(inserted_.size()) + (full_ ? 1 << 20 : 0)};
  }

 private:
  struct Inserted {
    Pose2 pose;
    Mat3 cov = Mat3::Zero();  // marginal robot covariance in the frame when inserted
  };
  void PredictWith(const Pose2& u, const Mat3& q);
  void Insert(const LaserScan& scan);

  GridLocalMapOptions options_;
  uint64_t id_;
  Pose2 x_;
  Mat3 p_rel_ = Mat3::Zero();  // robot relative to the grid near it
  bool full_ = false;
  std::vector<Inserted> inserted_;
  ProbabilityGrid grid_;
  RangeInserter inserter_;
  ScanAligner aligner_;
  AlignmentResult last_alignment_;
  bool last_matched_ = false;
  std::vector<Vec2> last_points_;
  RangeScan scratch_;
};

}  // namespace atlas
