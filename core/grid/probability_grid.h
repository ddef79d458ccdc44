#pragma once
// A bounded 2D probability grid, the dense submap of a map-frame (Hess et al. 2016, Section
// IV-B "Submaps"): each cell holds the probability that it is occupied, or "unknown" until a
// ray or a return first touches it. Values are stored as 15-bit integers linear in probability
// over [min_probability, max_probability] (0 = unknown), so that updates are table lookups
// (range_inserter.h).
//
// Cells lie on one global lattice: global cell g covers [g r, (g + 1) r) in the submap frame, r
// the resolution. A grid is a window of that lattice (GridLimits). A growing grid starts empty,
// enlarges its window (at least doubling a side, lattice-aligned, so values keep their cells)
// when asked to cover points outside it, and never exceeds max_cells per side; a grid built
// with fixed bounds never grows. The values' storage is exactly width x height.
// No I/O; never throws.

#include <cstdint>
#include <vector>

#include "core/geometry/se2.h"
#include "core/grid/grid_options.h"

namespace atlas {

struct CellIndex {
  int x = 0;
  int y = 0;
  bool operator==(const CellIndex&) const = default;
};

// A window of the global lattice: storage cell (i, j) is global cell (offset.x + i,
// offset.y + j).
struct GridLimits {
  double resolution = 0.05;
  CellIndex offset;
  int width = 0;
  int height = 0;

  // The storage cell containing p (maybe outside the window).
  CellIndex CellOf(const Vec2& p) const;
  // p in storage-cell units: CellOf(p) is its floor.
  Vec2 CellCoordinates(const Vec2& p) const;
  Vec2 CenterOf(const CellIndex& c) const;
  bool Contains(const CellIndex& c) const {
    return c.x >= 0 && c.y >= 0 && c.x < width && c.y < height;
  }
  int IndexOf(const CellIndex& c) const { return c.y * width + c.x; }
};

class ProbabilityGrid {
 public:
  static constexpr uint16_t kUnknown = 0;
  static constexpr uint16_t kMaxValue = 32767;

  // A growing grid, empty until the first GrowToCover.
  explicit ProbabilityGrid(const ProbabilityGridOptions& options);
  // A grid with fixed bounds: the cells covering [min, max] (at most max_cells per side,
  // counted from min); it never grows.
  ProbabilityGrid(const ProbabilityGridOptions& options, const Vec2& min, const Vec2& max);

  // Enlarges a growing grid so that it covers the box [min, max], as far as max_cells allows.
  // Returns true when the whole box is covered afterwards.
  bool GrowToCover(const Vec2& min, const Vec2& max);

  // Sets a growing grid's window and values as they were saved (its resolution stays: the
  // caller checks that it is the saved one), so that a grid read back is the one written,
  // window included. False, and the grid unchanged, when the grid does not grow, the window is
  // empty, wider or higher than max_cells or reaches beyond kMaxCellIndex cells from the
  // lattice's origin, `values` is not width x height or holds a value above kMaxValue.
  static constexpr int kMaxCellIndex = 1 << 30;
  bool Restore(const CellIndex& offset, int width, int height, std::vector<uint16_t> values);

  const GridLimits& limits() const { return limits_; }
  const ProbabilityGridOptions& options() const { return options_; }
  bool grows() const { return grows_; }

  // The stored value of a cell; kUnknown outside the window.
  uint16_t Value(const CellIndex& c) const {
    return limits_.Contains(c) ? values_[limits_.IndexOf(c)] : kUnknown;
  }
  bool IsKnown(const CellIndex& c) const { return Value(c) != kUnknown; }
  // The probability of a cell; min_probability when unknown or outside.
  double Probability(const CellIndex& c) const { return ProbabilityOfValue(Value(c)); }

  double ProbabilityOfValue(uint16_t value) const;
  // The value of probability p (clamped to [min_probability, max_probability]); never kUnknown.
  uint16_t ValueOfProbability(double p) const;

  int known_cells() const { return known_cells_; }
  // Storage, width x height values row by row (y major); for the inserter and the matchers.
  const std::vector<uint16_t>& values() const { return values_; }
  std::vector<uint16_t>& mutable_values() { return values_; }
  void AddKnownCells(int n) { known_cells_ += n; }

 private:
  // Resizes the window to [offset, offset + size) keeping every value in its global cell.
  void Reshape(const CellIndex& offset, int width, int height);

  ProbabilityGridOptions options_;
  bool grows_ = true;
  GridLimits limits_;
  std::vector<uint16_t> values_;
  int known_cells_ = 0;
};

// The centres of the cells whose probability is at least `min_probability`, in the submap
// frame (a submap's occupied cells as a point set for the matchers).
std::vector<Vec2> OccupiedCellCenters(const ProbabilityGrid& grid, double min_probability);

}  // namespace atlas
