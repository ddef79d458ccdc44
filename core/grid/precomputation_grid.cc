#include "core/grid/precomputation_grid.h"

#include <algorithm>
#include <cmath>

namespace atlas {

PrecomputationGrid::PrecomputationGrid(const ProbabilityGrid& grid)
    : width_(1), stride_(grid.limits().width), rows_(grid.limits().height) {
  const ProbabilityGridOptions& o = grid.options();
  values_.resize(static_cast<size_t>(stride_) * rows_);
  const std::vector<uint16_t>& cells = grid.values();
  for (size_t i = 0; i < cells.size(); ++i) {
    if (cells[i] == ProbabilityGrid::kUnknown) continue;
    const double t = (grid.ProbabilityOfValue(cells[i]) - o.min_probability) /
                     (o.max_probability - o.min_probability);
    values_[i] = static_cast<uint8_t>(std::clamp(std::lround(255.0 * t), 0L, 255L));
  }
}

PrecomputationGrid PrecomputationGrid::Coarser(const PrecomputationGrid& finer) {
  PrecomputationGrid g;
  g.width_ = 2 * finer.width_;
  g.stride_ = finer.stride_ + finer.width_;
  g.rows_ = finer.rows_ + finer.width_;
  g.values_.resize(static_cast<size_t>(g.stride_) * g.rows_);
  const int h = finer.width_;
  // Cell c of this level: the max of the finer level's blocks at c, c + h (x and y).
  for (int y = 0; y < g.rows_; ++y) {
    const int cy = y - (g.width_ - 1);
    for (int x = 0; x < g.stride_; ++x) {
      const int cx = x - (g.width_ - 1);
      g.values_[static_cast<size_t>(y) * g.stride_ + x] =
          std::max(std::max(finer.At(CellIndex{cx, cy}), finer.At(CellIndex{cx + h, cy})),
                   std::max(finer.At(CellIndex{cx, cy + h}), finer.At(CellIndex{cx + h, cy + h})));
    }
  }
  return g;
}

PrecomputationGridStack::PrecomputationGridStack(const ProbabilityGrid& grid, int depth)
    : limits_(grid.limits()),
      min_probability_(grid.options().min_probability),
      max_probability_(grid.options().max_probability) {
  levels_.reserve(depth);
  levels_.emplace_back(grid);
  for (int k = 1; k < depth; ++k) levels_.push_back(PrecomputationGrid::Coarser(levels_.back()));
}

double PrecomputationGridStack::MeanProbability(int64_t score, int points) const {
  if (points <= 0) return min_probability_;
  return min_probability_ +
         (max_probability_ - min_probability_) * static_cast<double>(score) / (255.0 * points);
}

}  // namespace atlas
