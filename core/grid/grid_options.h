#pragma once
// The options of core/grid, one struct validated once at start-up (Validate()). Defaults
// follow Hess et al. 2016 ("Real-Time Loop Closure in 2D LIDAR SLAM", Section IV: 5 cm cells,
// hit 0.55, miss 0.49) and Olson 2009 ("Real-time correlative scan matching").

#include <string>

namespace atlas {

// The probability grid and its hit/miss updates (probability_grid.h, range_inserter.h).
struct ProbabilityGridOptions {
  double resolution = 0.05;  // metres per cell side
  // The grid never exceeds this many cells per side (growth stops there; returns beyond it
  // are dropped and their rays clipped). 1024 cells of 5 cm: 51.2 m.
  int max_cells = 1024;
  int initial_cells = 64;          // cells per side of a growing grid when it is first used
  double hit_probability = 0.55;   // P(occupied | return in the cell)
  double miss_probability = 0.49;  // P(occupied | ray passed through the cell)
  double min_probability = 0.1;    // clamp; also the value an unknown cell scores
  double max_probability = 0.9;
  std::string Validate() const;
};

// Conversion of a laser scan into a RangeScan (range_inserter.h).
struct RangeScanOptions {
  double min_range = 0.1;   // metres; shorter returns are not used
  double max_range = 60.0;  // metres; returns at or beyond it count as "no return"
  // A beam without a return marks free space up to this many metres only (0: not at all).
  double no_return_free_range = 5.0;
  // A return whose surface (through it and either neighbouring return) meets the beam at less
  // than this angle is not used at all, neither hit nor ray (0: every return is used). At
  // grazing incidence the returns sample a wall more sparsely than the cells and the ray crosses
  // the wall's cells, so the grid's texture along the wall would be the beams' pattern, which a
  // scan matches best from where it was inserted (a robot "sticking" along a corridor).
  double min_incidence = 0.0;  // radians
  std::string Validate() const;
};

// Scan-to-grid alignment (scan_alignment.h): a correlative search, then Levenberg-Marquardt
// on the bicubic interpolation of the grid.
struct ScanAlignmentOptions {
  double linear_window = 0.15;   // metres either side of the initial pose, x and y
  double angular_window = 0.09;  // radians either side of the initial heading
  // The correlative search's heading step: Hess eq. 7 for the farthest point, but not finer
  // than this (far returns would otherwise make it a fraction of a milliradian).
  double min_angular_step = 0.005;  // radians
  int max_iterations = 20;
  // Stop when a step is shorter (metres, and radians x 1 m): the residuals do not vanish at the
  // optimum, so Gauss-Newton converges linearly (about 0.8 per iteration on the test room).
  double convergence_step = 0.001;
  int min_points = 20;
  double min_score = 0.3;  // mean probability of the points at the correlative optimum
  // A direction of (x, y, theta x rms radius) whose surface information (scan_alignment.h)
  // is below this fraction of the largest is reported as unconstrained (a corridor's length).
  double degenerate_ratio = 0.01;
  double normal_radius = 0.3;  // metres: the neighbours a point's surface normal is fitted to
  double unconstrained_sigma = 10.0;  // metres (radians x rms radius) given to such directions
  double min_residual_sigma = 0.05;   // floor of the residual scale of the covariance
  std::string Validate() const;
};

// Multi-resolution branch-and-bound search (precomputation_grid.h, branch_and_bound.h).
struct BranchAndBoundOptions {
  int depth = 6;                 // precomputed levels 0..depth-1; level k max-pools 2^k cells
  double linear_window = 2.0;    // metres either side of the centre, x and y
  double angular_window = 0.35;  // radians either side of the centre's heading
  double min_score = 0.0;        // mean probability; placements scoring less are not returned
  // The peak of the best placement: placements within this distance (per axis) and angle of
  // it are not candidates for the runner-up (Condition 2's margin).
  double peak_distance = 0.3;  // metres
  double peak_angle = 0.1;     // radians
  // Above 0, Condition 2 as a decision (branch_and_bound.h): the runner-up pass looks only for
  // a placement within this of the best's score and stops at the first it finds.
  double rival_margin = 0.0;
  std::string Validate() const;
};

struct GridOptions {
  ProbabilityGridOptions grid;
  RangeScanOptions range;
  ScanAlignmentOptions alignment;
  BranchAndBoundOptions search;
  std::string Validate() const;  // empty when valid, else the first problem found
};

}  // namespace atlas
