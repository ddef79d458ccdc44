#pragma once
// Multi-resolution grids for branch-and-bound matching (Olson 2009, Section IV "multi-level
// resolution"; Hess et al. 2016, Section V-C "precomputed grids"). Level k holds, for every
// cell c, the maximum over the 2^k x 2^k block of cells [c, c + 2^k) of the grid's quantised
// probability, so that the sum over a scan's cells at level k bounds from above the score of
// every placement whose translation lies in that block (eq. 15-16 of Hess). Values are 8-bit:
// 0 for unknown or min_probability, 255 for max_probability, linear in between. Level k is
// built from level k-1 by a max over four cells; memory is sum_k (W + 2^k - 1)(H + 2^k - 1)
// bytes. No I/O.

#include <cstdint>
#include <vector>

#include "core/grid/probability_grid.h"

namespace atlas {

class PrecomputationGrid {
 public:
  // Level 0 of `grid`: its cells quantised.
  explicit PrecomputationGrid(const ProbabilityGrid& grid);
  // The level of twice the width of `finer`.
  static PrecomputationGrid Coarser(const PrecomputationGrid& finer);
  // The same level with no row filled yet (all 0); FillRows(finer, 0, rows()) completes it.
  static PrecomputationGrid EmptyCoarser(const PrecomputationGrid& finer);
  // Fills rows [begin, end) of this level (made by EmptyCoarser(finer)) from `finer`.
  void FillRows(const PrecomputationGrid& finer, int begin, int end);

  // Max over [c, c + width) in both axes of the level-0 values; c in the grid's storage cells.
  // 0 where the block lies wholly outside the grid.
  uint8_t At(const CellIndex& c) const {
    const int x = c.x + width_ - 1, y = c.y + width_ - 1;
    if (x < 0 || y < 0 || x >= stride_ || y >= rows_) return 0;
    return values_[static_cast<size_t>(y) * stride_ + x];
  }
  int width() const { return width_; }
  int rows() const { return rows_; }
  int stride() const { return stride_; }

 private:
  PrecomputationGrid() = default;

  int width_ = 1;   // 2^k
  int stride_ = 0;  // grid width + width - 1
  int rows_ = 0;    // grid height + width - 1
  std::vector<uint8_t> values_;
};

// Levels 0 .. depth-1 of one grid, built once and shared by many searches. The levels above 0
// may be built in slices (Build), so that a large grid's build costs no single step more than a
// bound; a search needs a complete() stack.
class PrecomputationGridStack {
 public:
  enum class Building { kAtOnce, kInSlices };
  // kInSlices: level 0 only; Build() makes the rest.
  PrecomputationGridStack(const ProbabilityGrid& grid, int depth,
                          Building building = Building::kAtOnce);

  // Fills at most about `max_cells` cells of the missing levels (whole rows, at least one);
  // returns the cells filled. complete() once every level is built.
  int64_t Build(int64_t max_cells);
  bool complete() const { return static_cast<int>(levels_.size()) == depth_ && next_row_ == 0; }

  const PrecomputationGrid& Level(int k) const { return levels_[k]; }
  int depth() const { return depth_; }
  const GridLimits& limits() const { return limits_; }
  double min_probability() const { return min_probability_; }
  double max_probability() const { return max_probability_; }
  // The mean probability that a score (sum of level values) over `points` points stands for.
  double MeanProbability(int64_t score, int points) const;

 private:
  std::vector<PrecomputationGrid> levels_;
  int depth_ = 1;
  int next_row_ = 0;  // of levels_.back() while it is being filled
  GridLimits limits_;
  double min_probability_ = 0.0;
  double max_probability_ = 1.0;
};

}  // namespace atlas
