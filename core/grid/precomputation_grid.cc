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

PrecomputationGrid PrecomputationGrid::EmptyCoarser(const PrecomputationGrid& finer) {
  PrecomputationGrid g;
  g.width_ = 2 * finer.width_;
  g.stride_ = finer.stride_ + finer.width_;
  g.rows_ = finer.rows_ + finer.width_;
  g.values_.assign(static_cast<size_t>(g.stride_) * g.rows_, 0);
  return g;
}

PrecomputationGrid PrecomputationGrid::Coarser(const PrecomputationGrid& finer) {
  PrecomputationGrid g = EmptyCoarser(finer);
  g.FillRows(finer, 0, g.rows_);
  return g;
}

void PrecomputationGrid::FillRows(const PrecomputationGrid& finer, int begin, int end) {
  // Cell (x, y) of this level is the max of the finer level's stored cells (x - h, y - h),
  // (x, y - h), (x - h, y) and (x, y), each 0 outside the finer level.
  const int h = finer.width_, fs = finer.stride_;  // stride_ == fs + h
  auto finer_row_max = [&](int fy, uint8_t* out) {
    if (fy < 0 || fy >= finer.rows_) return;
    const uint8_t* row = finer.values_.data() + static_cast<size_t>(fy) * fs;
    const int both_from = std::min(h, fs);  // below: row[x] only; [fs, h) has neither
    for (int x = 0; x < both_from; ++x) out[x] = std::max(out[x], row[x]);
    for (int x = h; x < fs; ++x) out[x] = std::max({out[x], row[x - h], row[x]});
    for (int x = std::max(fs, h); x < stride_; ++x) out[x] = std::max(out[x], row[x - h]);
  };
  for (int y = std::max(begin, 0); y < std::min(end, rows_); ++y) {
    uint8_t* out = values_.data() + static_cast<size_t>(y) * stride_;
    std::fill(out, out + stride_, 0);
    finer_row_max(y - h, out);
    finer_row_max(y, out);
  }
}

PrecomputationGridStack::PrecomputationGridStack(const ProbabilityGrid& grid, int depth,
                                                 Building building)
    : depth_(std::max(depth, 1)),
      limits_(grid.limits()),
      min_probability_(grid.options().min_probability),
      max_probability_(grid.options().max_probability) {
  levels_.reserve(depth_);
  levels_.emplace_back(grid);
  if (building == Building::kAtOnce) {
    for (int k = 1; k < depth_; ++k) levels_.push_back(PrecomputationGrid::Coarser(levels_.back()));
  }
}

int64_t PrecomputationGridStack::Build(int64_t max_cells) {
  int64_t filled = 0;
  while (!complete() && (filled == 0 || filled < max_cells)) {
    if (next_row_ == 0) levels_.push_back(PrecomputationGrid::EmptyCoarser(levels_.back()));
    PrecomputationGrid& level = levels_.back();
    const int64_t per_row = level.stride();
    const int rows = static_cast<int>(std::clamp<int64_t>(
        (max_cells - filled) / std::max<int64_t>(per_row, 1), 1, level.rows() - next_row_));
    level.FillRows(levels_[levels_.size() - 2], next_row_, next_row_ + rows);
    filled += per_row * rows;
    next_row_ += rows;
    if (next_row_ == level.rows()) next_row_ = 0;
  }
  return filled;
}

double PrecomputationGridStack::MeanProbability(int64_t score, int points) const {
  if (points <= 0) return min_probability_;
  return min_probability_ +
         (max_probability_ - min_probability_) * static_cast<double>(score) / (255.0 * points);
}

}  // namespace atlas
