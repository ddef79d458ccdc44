#include "core/grid/probability_grid.h"

#include <algorithm>
#include <cassert>
#include <cmath>

namespace atlas {
namespace {

// The global lattice cell containing coordinate v.
int GlobalCell(double v, double resolution) { return static_cast<int>(std::floor(v / resolution)); }

// New extent of one axis: the window [lo, lo + size) must reach [need_lo, need_hi] (global
// cells). Grows by at least a factor two, at most to `max_size`; when the cap does not allow all
// of it, the budget is shared between the two sides. Returns the new (lo, size).
std::pair<int, int> GrowAxis(int lo, int size, int need_lo, int need_hi, int max_size) {
  const int grow_lo = std::max(0, lo - need_lo);
  const int grow_hi = std::max(0, need_hi - (lo + size - 1));
  if (grow_lo == 0 && grow_hi == 0) return {lo, size};
  const int budget = max_size - size;
  if (grow_lo + grow_hi <= budget) {
    const int new_size = std::min(max_size, std::max(size + grow_lo + grow_hi, 2 * size));
    const int spare = new_size - (size + grow_lo + grow_hi);
    // The spare cells go half to each side, clamped so the old window stays inside.
    return {lo - grow_lo - spare / 2, new_size};
  }
  const int take_lo = std::min(grow_lo, std::max(budget - grow_hi, budget / 2));
  const int take_hi = std::min(grow_hi, budget - take_lo);
  return {lo - take_lo, size + take_lo + take_hi};
}

}  // namespace

CellIndex GridLimits::CellOf(const Vec2& p) const {
  return CellIndex{GlobalCell(p.x(), resolution) - offset.x,
                   GlobalCell(p.y(), resolution) - offset.y};
}

Vec2 GridLimits::CellCoordinates(const Vec2& p) const {
  return Vec2(p.x() / resolution - offset.x, p.y() / resolution - offset.y);
}

Vec2 GridLimits::CenterOf(const CellIndex& c) const {
  return Vec2((offset.x + c.x + 0.5) * resolution, (offset.y + c.y + 0.5) * resolution);
}

ProbabilityGrid::ProbabilityGrid(const ProbabilityGridOptions& options) : options_(options) {
  assert(options_.Validate().empty());
  limits_.resolution = options_.resolution;
}

ProbabilityGrid::ProbabilityGrid(const ProbabilityGridOptions& options, const Vec2& min,
                                 const Vec2& max)
    : options_(options), grows_(false) {
  assert(options_.Validate().empty());
  limits_.resolution = options_.resolution;
  const CellIndex lo{GlobalCell(min.x(), options_.resolution),
                     GlobalCell(min.y(), options_.resolution)};
  const CellIndex hi{GlobalCell(max.x(), options_.resolution),
                     GlobalCell(max.y(), options_.resolution)};
  Reshape(lo, std::clamp(hi.x - lo.x + 1, 1, options_.max_cells),
          std::clamp(hi.y - lo.y + 1, 1, options_.max_cells));
}

bool ProbabilityGrid::GrowToCover(const Vec2& min, const Vec2& max) {
  const double r = limits_.resolution;
  const CellIndex lo{GlobalCell(min.x(), r), GlobalCell(min.y(), r)};
  const CellIndex hi{GlobalCell(max.x(), r), GlobalCell(max.y(), r)};
  auto covered = [&] {
    const GridLimits& l = limits_;
    return lo.x >= l.offset.x && lo.y >= l.offset.y && hi.x < l.offset.x + l.width &&
           hi.y < l.offset.y + l.height;
  };
  if (covered()) return true;
  if (!grows_) return false;
  CellIndex offset = limits_.offset;
  int width = limits_.width, height = limits_.height;
  if (width == 0) {
    // First use: an initial window centred on the box.
    width = height = options_.initial_cells;
    offset = CellIndex{lo.x + (hi.x - lo.x) / 2 - width / 2, lo.y + (hi.y - lo.y) / 2 - height / 2};
  }
  const auto [x, w] = GrowAxis(offset.x, width, lo.x, hi.x, options_.max_cells);
  const auto [y, h] = GrowAxis(offset.y, height, lo.y, hi.y, options_.max_cells);
  Reshape(CellIndex{x, y}, w, h);
  return covered();
}

bool ProbabilityGrid::Restore(const CellIndex& offset, int width, int height,
                              std::vector<uint16_t> values) {
  const auto within = [](int lo, int size, int max_size) {
    return size > 0 && size <= max_size && lo >= -kMaxCellIndex && lo <= kMaxCellIndex - size;
  };
  if (!grows_ || !within(offset.x, width, options_.max_cells) ||
      !within(offset.y, height, options_.max_cells) ||
      values.size() != static_cast<size_t>(width) * static_cast<size_t>(height))
    return false;
  if (std::any_of(values.begin(), values.end(), [](uint16_t v) { return v > kMaxValue; }))
    return false;
  known_cells_ =
      static_cast<int>(values.size() - std::count(values.begin(), values.end(), kUnknown));
  values_ = std::move(values);
  limits_.offset = offset;
  limits_.width = width;
  limits_.height = height;
  return true;
}

void ProbabilityGrid::Reshape(const CellIndex& offset, int width, int height) {
  assert(width <= options_.max_cells && height <= options_.max_cells);
  std::vector<uint16_t> values(static_cast<size_t>(width) * height, kUnknown);
  const GridLimits& old = limits_;
  for (int j = 0; j < old.height; ++j) {
    const int y = old.offset.y + j - offset.y;
    for (int i = 0; i < old.width; ++i) {
      const int x = old.offset.x + i - offset.x;
      if (x >= 0 && y >= 0 && x < width && y < height) {
        values[static_cast<size_t>(y) * width + x] = values_[old.IndexOf(CellIndex{i, j})];
      }
    }
  }
  values_.swap(values);
  limits_.offset = offset;
  limits_.width = width;
  limits_.height = height;
}

double ProbabilityGrid::ProbabilityOfValue(uint16_t value) const {
  if (value == kUnknown) return options_.min_probability;
  return options_.min_probability + (options_.max_probability - options_.min_probability) *
                                        (value - 1) / static_cast<double>(kMaxValue - 1);
}

uint16_t ProbabilityGrid::ValueOfProbability(double p) const {
  const double t = (std::clamp(p, options_.min_probability, options_.max_probability) -
                    options_.min_probability) /
                   (options_.max_probability - options_.min_probability);
  return static_cast<uint16_t>(1 + std::lround(t * (kMaxValue - 1)));
}

std::vector<Vec2> OccupiedCellCenters(const ProbabilityGrid& grid, double min_probability) {
  std::vector<Vec2> points;
  const GridLimits& l = grid.limits();
  for (int j = 0; j < l.height; ++j) {
    for (int i = 0; i < l.width; ++i) {
      const CellIndex c{i, j};
      if (grid.IsKnown(c) && grid.Probability(c) >= min_probability) {
        points.push_back(l.CenterOf(c));
      }
    }
  }
  return points;
}

}  // namespace atlas
