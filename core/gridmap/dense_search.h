#pragma once
// The search shared by w (grid_map_bootstrapper.h) and map-matching (grid_map_matcher.h):
// points placed in a frame's grid by multi-resolution branch and bound (core/grid/
// branch_and_bound.h; Olson 2009; Hess et al. 2016, Section V) over a window of 3 sigma of a
// prior (clamped to the options' windows), then refined by ScanAligner (least squares on the
// bicubic grid, covariance from the match, over information_scale plus the floors of
// GridLocalMapOptions).
//
// Outcomes, in the order they are checked:
//  - kWorkBound: the search exceeded max_nodes (it cannot show that the best is unique);
//  - kLowScore: the best placement scores below min_score (the points do not lie in the grid);
//  - kRepetitive: the runner-up outside the best's peak comes within min_margin of it
//    (Condition 2: a placement the window cannot tell apart);
//  - kUnconstrained: the refinement leaves a direction unfixed (a corridor's length), or fails;
//  - kFound.

#include <cstdint>
#include <memory>
#include <utility>
#include <vector>

#include "core/grid/precomputation_grid.h"
#include "core/gridmap/grid_local_map.h"

namespace atlas {

enum class DenseOutcome { kFound, kWorkBound, kLowScore, kRepetitive, kUnconstrained };

struct DenseResult {
  DenseOutcome outcome = DenseOutcome::kLowScore;
  UncertainPose pose;  // kFound: the points' frame in the grid's frame
  double score = 0.0;
  double margin = 0.0;
  int64_t nodes = 0;
};

// The precomputed grids of the last few maps searched in, by GridLocalMap::Revision (not
// thread-safe: the Atlas steps on one thread).
class PrecomputedGrids {
 public:
  explicit PrecomputedGrids(int depth) : depth_(depth) {}
  const PrecomputationGridStack& Of(const GridLocalMap& map);

 private:
  static constexpr size_t kCached = 6;
  struct Cached {
    std::pair<uint64_t, int> revision;
    std::unique_ptr<PrecomputationGridStack> grids;
  };
  int depth_;
  std::vector<Cached> cache_;
  size_t next_ = 0;
};

// At most `max` of `points`, evenly spread over the sequence.
std::vector<Vec2> EvenSubsample(const std::vector<Vec2>& points, int max);

// `grids` must be built from `grid`. `prior`: the window's centre and, by its covariance, size.
DenseResult SearchAndRefine(const PrecomputationGridStack& grids, const ProbabilityGrid& grid,
                            const std::vector<Vec2>& points, const UncertainPose& prior,
                            const GridSearchOptions& search, const GridLocalMapOptions& map);

}  // namespace atlas
