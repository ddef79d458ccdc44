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
//    (Condition 2: a placement the window cannot tell apart); or, when the prior's 3 sigma
//    reaches beyond the window, a placement at the best's heading within that 3 sigma (at most
//    max_repetition_window) and outside the best's peak does (a corridor's period longer than
//    the window: the frame repeats where the prior still allows the robot to be);
//  - kWorkBound also when that second search exceeds max_nodes;
//  - kUnconstrained: the refinement leaves a direction unfixed (a corridor's length), or fails;
//  - kFound.

#include <cstdint>
#include <memory>
#include <utility>
#include <vector>

#include "core/grid/branch_and_bound.h"
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
// thread-safe: the Atlas steps on one thread). A stack may be handed out before it is complete
// (kInSlices): its searches build it first (DenseSearch).
class PrecomputedGrids {
 public:
  explicit PrecomputedGrids(int depth) : depth_(depth) {}
  // Built in slices (PrecomputationGridStack::Building::kInSlices) when not cached.
  std::shared_ptr<PrecomputationGridStack> Of(const GridLocalMap& map);

 private:
  static constexpr size_t kCached = 16;  // a 512 x 512 grid's stack of 6 levels: about 1.8 MB
  struct Cached {
    std::pair<uint64_t, int> revision;
    std::shared_ptr<PrecomputationGridStack> grids;
  };
  int depth_;
  std::vector<Cached> cache_;
  size_t next_ = 0;
};

// At most `max` of `points`, evenly spread over the sequence.
std::vector<Vec2> EvenSubsample(const std::vector<Vec2>& points, int max);
// The points a search looks for: those of `points` (robot frame) within
// options.max_point_range of the robot, evenly subsampled to options.max_points.
std::vector<Vec2> SearchPoints(const std::vector<Vec2>& points, const GridSearchOptions& options);

// Points searched for in a grid (the outcomes above), in slices of bounded work so that one
// search can be spread over several steps: Continue(grid, work) does at most about `work` cell
// visits (precomputed cells filled, points scored at a node, points discretised), and returns
// true once result() is final. The refinement runs in the call that ends the search when
// half of that call's work is left, else in the next. The result does not
// depend on the slicing. `grids` must be built (or be building) from the grid passed to
// Continue; `prior`: the window's centre and, by its covariance, size.
class DenseSearch {
 public:
  DenseSearch(std::shared_ptr<PrecomputationGridStack> grids, std::vector<Vec2> points,
              const UncertainPose& prior, const GridSearchOptions& search,
              const GridLocalMapOptions& map);
  bool Continue(const ProbabilityGrid& grid, int64_t work);
  bool done() const { return phase_ == Phase::kDone; }
  const DenseResult& result() const { return result_; }

 private:
  enum class Phase { kPrecompute, kSearch, kBeyond, kRefine, kDone };
  enum class SliceEnd { kDone, kMore, kWorkBound };
  // Runs `search` for what `work` (cell visits) allows, at most max_nodes nodes in all; takes
  // what it used from `work`.
  SliceEnd RunSlice(BranchAndBoundSearch& search, int64_t per_node, int64_t* work) const;
  bool EndWorkBound();  // the outcome kWorkBound; true (the search has ended)
  std::shared_ptr<PrecomputationGridStack> grids_;
  std::vector<Vec2> points_;
  UncertainPose prior_;
  GridSearchOptions search_;
  GridLocalMapOptions map_;
  double prior_three_sigma_;  // along the prior's widest axis, metres
  std::unique_ptr<BranchAndBoundSearch> bnb_;
  std::unique_ptr<BranchAndBoundSearch> beyond_;  // the repetition search (kRepetitive above)
  Phase phase_ = Phase::kPrecompute;
  DenseResult result_;
};

}  // namespace atlas
