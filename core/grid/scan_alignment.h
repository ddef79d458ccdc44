#pragma once
// Scan-to-submap alignment: the pose of a scan in its submap's frame (Hess et al. 2016,
// Section IV-C, with the correlative start of Olson 2009).
//
//  1. Correlative search: every placement of a window around the initial pose (whole cells in
//     x and y, heading steps of discrete_scans.h) is scored by the mean probability of the
//     grid cells its points fall in; the best, nearest the initial pose among equals, starts:
//  2. Levenberg-Marquardt on the interpolated grid (interpolated_grid.h):
//       x* = argmin_x  sum_i (1 - M(T_x q_i))^2
//     with q_i the scan's points (scan frame) and M the bicubic probability.
//  3. Covariance from the match: H = J^T J at x*, s^2 = sum_i r_i^2 / (n - 3) (at least
//     min_residual_sigma^2), C = s^2 H^+ (pseudo-inverse).
//  4. Directions the grid does not fix (a corridor's length, a lone wall), from the scan's own
//     surfaces (point-to-line information, Censi 2007): each point explained at x* (probability
//     at least 0.5) whose neighbours in scan order within normal_radius lie on a line adds
//     j j^T, j = (n, n . d(T_x q)/d theta), n the line's normal; one whose neighbours do not (a
//     corner, a chair leg) adds half of it for both axes. In the coordinates (x, y, L theta),
//     L the points' rms radius so that metres and radians compare, eigen-directions of this G
//     below degenerate_ratio times its largest eigenvalue are "unconstrained": they are
//     reported, and C gets unconstrained_sigma along them (their share of C removed first),
//     so that the caller takes the odometry there. J^T J cannot tell: the grid's cell-scale
//     texture along a wall (where scans were inserted from) feeds it in every direction, and so
//     does the response of the correlative search (its fit over a few cells scored the test
//     corridor's length like the room's weakest direction at some steps). On the test
//     corridor G's length scores 0.0006-0.003 of its largest, in the test room the weakest
//     direction 0.05-0.2 (0.01 while the grid holds one scan).
//
// Typed outcomes, never throws. Work is bounded: (2 linear_window / r + 1)^2 x headings x
// points lookups, then at most max_iterations passes over the points.

#include <cstdint>
#include <vector>

#include "core/geometry/se2.h"
#include "core/grid/discrete_scans.h"
#include "core/grid/grid_options.h"
#include "core/grid/probability_grid.h"

namespace atlas {

enum class AlignmentOutcome {
  kAligned,        // every direction fixed by the grid
  kUnconstrained,  // aligned, but `unconstrained` directions are not fixed: take odometry there
  kTooFewPoints,   // fewer than min_points
  kLowScore,       // the correlative optimum scores below min_score: nothing to align to
};
const char* ToString(AlignmentOutcome o);

struct AlignmentResult {
  AlignmentOutcome outcome = AlignmentOutcome::kTooFewPoints;
  // The scan's pose in the submap frame; the initial pose (zero covariance) unless aligned.
  UncertainPose pose;
  Mat3 information = Mat3::Zero();          // H / s^2, over (x, y, theta)
  Mat3 surface_information = Mat3::Zero();  // G above, over (x, y, theta)
  // Columns 0 .. unconstrained-1: unit directions of (x, y, radius theta) that the grid does
  // not fix.
  int unconstrained = 0;
  Mat3 unconstrained_directions = Mat3::Zero();
  double radius = 0.0;             // metres, L above
  double correlative_score = 0.0;  // mean cell probability at the correlative optimum
  double score = 0.0;              // mean interpolated probability at x*
  int points = 0;
  int iterations = 0;
};

class ScanAligner {
 public:
  explicit ScanAligner(const ScanAlignmentOptions& options);

  // Aligns `points` (scan frame) to `grid`, starting from `initial` (scan in submap frame).
  AlignmentResult Align(const ProbabilityGrid& grid, const std::vector<Vec2>& points,
                        const Pose2& initial);

  const ScanAlignmentOptions& options() const { return options_; }

 private:
  // The correlative optimum around `initial`; fills out's correlative_score.
  Pose2 CorrelativeSearch(const ProbabilityGrid& grid, const std::vector<Vec2>& points,
                          const Pose2& initial, AlignmentResult* out);

  ScanAlignmentOptions options_;
  DiscreteScans scans_;            // scratch
  std::vector<int64_t> row_sums_;  // scratch: one row of placements' sums
};

}  // namespace atlas
