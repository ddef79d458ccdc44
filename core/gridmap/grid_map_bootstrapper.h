#pragma once
// w of eq. 12 for grid map-frames (grid_local_map.h): the juvenile's pose solved from its own
// scans Z against the frame's grid, independently of the seed beyond the search window.
//
// Z's returns are placed in the current (last) robot frame by composing the odometry
// increments backwards, and searched for in the frame's grid by multi-resolution branch and
// bound (core/grid/branch_and_bound.h; Olson 2009, Hess et al. 2016, Section V) over a window
// of 3 sigma of the seed (clamped to [min, max] _window), centred on the juvenile's current
// pose; the best placement is refined by ScanAligner (least squares, covariance from the match).
// Outcomes:
//  - kFailed: the best placement scores below min_score (Z does not lie in this grid);
//  - kUndetermined (retried with more scans until the end of probation): the runner-up outside
//    the best's peak comes within min_margin of it (Condition 2: repetition the window cannot
//    tell apart), the refinement leaves a direction unconstrained (a corridor's length), or
//    the search exceeded max_nodes;
//  - kSolved: the refined pose with its covariance (over information_scale, plus the floors).

#include "core/atlas/hypothesis.h"
#include "core/gridmap/dense_search.h"
#include "core/gridmap/grid_local_map.h"

namespace atlas {

class GridMapBootstrapper : public PoseBootstrapper {
 public:
  // `options` must be valid (those the maps were made with).
  explicit GridMapBootstrapper(const GridLocalMapOptions& options) : options_(options) {}
  // `frame_map` must be a GridLocalMap (else kFailed); `map` proposes the window's centre and
  // `seed` its size.
  PoseBootstrap Solve(const LocalMap& map, const LocalMap& frame_map,
                      const std::vector<JuvenileScan>& z, const UncertainPose& seed) const override;
  // The same in slices of at most options.bootstrap.work_per_step (DenseSearch): the frame's
  // precomputed grids when not cached, the branch and bound, then the refinement. Z's points
  // are those at Begin.
  std::unique_ptr<BootstrapSearch> Begin(const LocalMap& map, const LocalMap& frame_map,
                                         const std::vector<JuvenileScan>& z,
                                         const UncertainPose& seed) const override;

 private:
  GridLocalMapOptions options_;
  mutable PrecomputedGrids grids_{options_.grid.search.depth};
};

}  // namespace atlas
