#pragma once
// Map-matching (paper, III-D) of grid map-frames (grid_local_map.h). Frame A is the dominant
// hypothesis's: its last scan, at the robot's pose in A, is searched for in frame B's grid by
// multi-resolution branch and bound (dense_search.h; as Hess et al. 2016, Section V, match a
// scan against a submap) over the window the Dijkstra projection's covariance allows (the robot
// moved into B through the prior, 3 sigma, clamped to the options' `match` windows), then
// refined by least squares. t = robot in A (-) robot in B, with both covariances: the robot's
// in A (relative to A's grid plus that grid's own error near it) and the match's in B plus
// B's grid's own error there (Condition 1).
// Condition 2: the best placement must lead the runner-up outside its peak by min_margin
// (kAmbiguous, kRepetitive otherwise), and t must lie inside the prior's gate (chi-square 3
// dof 99.9 % with both covariances; kOutsidePrior otherwise).
// The placement found gets at least match.min_sigma_* (the frames' grids are less consistent
// than GridCovarianceNear says: measured in docs/journal/dense-frames.md).
//
// Not done yet (docs/journal/dense-frames.md): frames without a prior (after a restart) are
// not matched (kTooFewLines), B's correlation with itself is not looked at, nor is either
// frame's free space. The precomputed grids of the last few frames searched in are kept.

#include <memory>
#include <utility>
#include <vector>

#include "core/atlas/map_matcher.h"
#include "core/gridmap/dense_search.h"
#include "core/gridmap/grid_local_map.h"

namespace atlas {

class GridMapMatcher : public MapMatcher {
 public:
  explicit GridMapMatcher(const GridLocalMapOptions& options) : options_(options) {}
  MapMatch Match(const LocalMap& a, const LocalMap& b, const UncertainPose* prior) const override;

 private:
  GridLocalMapOptions options_;
  mutable PrecomputedGrids grids_{options_.grid.search.depth};
};

}  // namespace atlas
