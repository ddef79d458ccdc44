#pragma once
// Multi-resolution branch-and-bound matching of a point set against a grid (Olson 2009,
// Section IV; Hess et al. 2016, Section V-B/C, Algorithm 3), for map-matching (Atlas paper,
// III-D) under Condition 2.
//
// The window around `center` (x, y, heading; discrete_scans.h) is covered by nodes: a heading
// and a block of 2^k x 2^k translations, scored with level k of a PrecomputationGridStack,
// which bounds every placement in the block from above. Depth-first, children best first, a
// node is cut when its bound does not exceed the best placement found so far; leaves (k = 0)
// are exact. Scores are integer sums of 8-bit cell values, so the result equals that of
// ExhaustiveSearch below (same score; the same placement when the maximum is unique).
//
// Condition 2's margin: a second pass finds the best placement outside the best one's peak
// (within peak_distance per axis and peak_angle of it), cutting nodes wholly inside the peak.
// A repetitive place (a corridor's doors, a row of pillars) then has a runner-up close to the
// best. With options.rival_margin > 0 the pass is a decision: it cuts every node that cannot
// score within rival_margin of the best and stops at the first placement that does (that is
// result().runner_up, and margin < rival_margin), so a unique best costs few nodes. The
// answer (margin below rival_margin or not) is that of the full pass.
//
// Outside a peak: given a placement `outside_of` (of this search's window), only placements
// outside its peak are searched and there is no runner-up pass; the best of them is result().best
// (with rival_margin > 0: the first found scoring at least min_score).
// This is Condition 2 beyond a window: is there another placement as good as one found?
//
// Sliceable: Run(max_nodes) scores at most max_nodes nodes and returns; later calls resume.
// The result does not depend on how the work was sliced. Memory: the binned points of every
// heading (headings x points cells) and a stack of at most depth frames of 4 children plus the
// top level's nodes. Never throws.

#include <cstdint>
#include <vector>

#include "core/geometry/se2.h"
#include "core/grid/discrete_scans.h"
#include "core/grid/grid_options.h"
#include "core/grid/precomputation_grid.h"

namespace atlas {

struct MatchPlacement {
  bool found = false;
  Pose2 pose;
  double score = 0.0;  // mean quantised probability of the points (unknown: min_probability)
  int64_t sum = 0;     // the integer score
  Placement placement;
};

struct BranchAndBoundResult {
  MatchPlacement best;       // found when some placement scores at least min_score
  MatchPlacement runner_up;  // the best placement outside best's peak, of any score
  int64_t nodes = 0;         // nodes scored
  // best.score - runner_up.score; best.score - min_probability when there is no runner-up.
  double margin = 0.0;
};

enum class SearchStatus { kRunning, kDone };

class BranchAndBoundSearch {
 public:
  // `grids` must be complete() and outlive the search; `points` are in the frame of the pose
  // searched for, and `center` is the window's centre (points' frame in the grid's frame).
  BranchAndBoundSearch(const PrecomputationGridStack& grids, const std::vector<Vec2>& points,
                       const Pose2& center, const BranchAndBoundOptions& options,
                       const Placement* outside_of = nullptr);

  // Scores at most `max_nodes` nodes (at least one); kDone when the search has finished.
  SearchStatus Run(int64_t max_nodes);
  bool done() const { return phase_ == Phase::kDone; }
  // Complete when done().
  const BranchAndBoundResult& result() const { return result_; }
  const SearchWindow& window() const { return window_; }

 private:
  enum class Phase { kBest, kRunnerUp, kDone };
  struct Node {
    Placement placement;
    int level = 0;
    int64_t score = 0;
  };
  struct Frame {
    std::vector<Node> nodes;
    size_t scored = 0;
    bool sorted = false;
    size_t next = 0;
  };

  int64_t Score(const Node& node) const;
  // Pushes a frame with the children of `node` (the top level's nodes when null).
  void PushChildren(const Node* node);
  void Finish(MatchPlacement* m, const Node& leaf) const;
  void StartRunnerUp();

  const PrecomputationGridStack& grids_;
  BranchAndBoundOptions options_;
  Pose2 center_;
  SearchWindow window_;
  DiscreteScans scans_;
  int64_t min_sum_ = 0;
  int64_t rival_floor_ = -1;  // the runner-up pass cuts nodes scoring no more
  Phase phase_ = Phase::kBest;
  std::vector<Frame> stack_;  // stack_[0] holds the top level's nodes
  int depth_ = 0;             // frames in use
  Peak peak_;
  bool outside_ = false;  // placements inside peak_ are not searched, no runner-up pass
  BranchAndBoundResult result_;
};

// Every placement of the window scored at level 0: the reference for BranchAndBoundSearch (and
// the correlative search of Olson 2009 without its speed-up). Ties go to the first placement in
// (heading, y, x) order. Memory: one integer per placement; for tests and measurements.
BranchAndBoundResult ExhaustiveSearch(const PrecomputationGridStack& grids,
                                      const std::vector<Vec2>& points, const Pose2& center,
                                      const BranchAndBoundOptions& options);

}  // namespace atlas
