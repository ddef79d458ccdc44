#pragma once
// Map-matching (paper, III-D) of grid map-frames (grid_local_map.h). Frame A is the dominant
// hypothesis's: its last scan, at the robot's pose in A, is searched for in frame B's grid by
// multi-resolution branch and bound (dense_search.h; as Hess et al. 2016, Section V, match a
// scan against a submap) over the window the Dijkstra projection's covariance allows (the robot
// moved into B through the prior, 3 sigma, clamped to the options' `match` windows), then
// refined by least squares. t = robot in A (-) robot in B, with both covariances: the robot's
// in A (relative to A's grid plus that grid's own error near it) and the match's in B plus
// B's grid's own error there (Condition 1).
// Condition 2 (paper, II-A; docs/design.md, "Dense frames"), checked in this order:
//  - the best placement must lead the runner-up outside its peak by min_margin, in the window
//    and, where the prior's 3 sigma reaches beyond it, at the best's heading over that 3 sigma
//    (dense_search.h; kAmbiguous, kRepetitive otherwise);
//  - t must lie inside the prior's gate (chi-square 3 dof 99.9 % with both covariances;
//    kOutsidePrior otherwise);
//  - free space: at t, neither frame's walls may stand where the other frame has seen through.
//    Of each frame's occupied cells within kFreeSpaceRadius of the robot, the fraction that
//    falls, moved into the other frame by t, where the other's grid is free must be at most
//    max_free_space_conflict (both ways; kRejected, kFreeSpace otherwise). The scan searched
//    for is placed on B's walls by construction; the rest of the two frames is what tells a
//    place from another that looks the same from where the robot stands.
// The placement found gets at least match.min_sigma_* (the frames' grids are less consistent
// than GridCovarianceNear says; docs/design.md, "Dense frames").
//
// Not done yet: frames without a prior (after a restart) are not matched (kTooFewLines). The
// precomputed grids of the last few frames searched in are kept (PrecomputedGrids).

#include <memory>
#include <utility>
#include <vector>

#include "core/atlas/map_matcher.h"
#include "core/gridmap/dense_search.h"
#include "core/gridmap/grid_local_map.h"

namespace atlas {

// Occupied: probability >= kFreeSpaceOccupied. Free: the cell and its 8 neighbours known, each
// below 0.5 (a wall one cell off its place is not in free space). Cells farther than
// kFreeSpaceRadius from the robot are not counted.
inline constexpr double kFreeSpaceOccupied = kOccupiedProbability;
inline constexpr double kFreeSpaceRadius = 8.0;  // metres

struct FreeSpaceConflict {
  int occupied = 0;  // b's occupied cells counted
  int in_free = 0;   // of those, the ones in a's free space
  double Fraction() const { return occupied > 0 ? static_cast<double>(in_free) / occupied : 0.0; }
};

// b's occupied cells within `radius` of `centre_b` (b's frame), moved into a's frame by
// `b_in_a`, against a's free space (as above).
FreeSpaceConflict FreeSpaceConflictOf(const ProbabilityGrid& a, const ProbabilityGrid& b,
                                      const Pose2& b_in_a, const Vec2& centre_b, double radius);

class GridMapMatcher : public MapMatcher {
 public:
  explicit GridMapMatcher(const GridLocalMapOptions& options) : options_(options) {}
  MapMatch Match(const LocalMap& a, const LocalMap& b, const UncertainPose* prior) const override;
  // The search of Match in slices of at most options.match.work_per_step (DenseSearch): B's
  // precomputed grids (built in slices when not cached), the branch and bound, then the
  // refinement and the tests above, each in later steps. `a`'s last scan and robot pose are
  // those at Begin.
  std::unique_ptr<MapMatchSearch> Begin(const LocalMap& a, const LocalMap& b,
                                        const UncertainPose* prior) const override;

 private:
  GridLocalMapOptions options_;
  mutable PrecomputedGrids grids_{options_.grid.search.depth};
};

}  // namespace atlas
