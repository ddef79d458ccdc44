#pragma once
// A smooth view of a probability grid for least-squares alignment (Hess et al. 2016, Section
// IV-C: "bicubic interpolation" of the grid, whose gradient the solver follows). Cell
// probabilities (min_probability where unknown) sit at cell centres and are joined by
// Catmull-Rom bicubic patches: continuous value and gradient, exact at the centres. No I/O.

#include "core/geometry/se2.h"
#include "core/grid/probability_grid.h"

namespace atlas {

class InterpolatedGrid {
 public:
  // Keeps a reference: `grid` must outlive this view and not change while it is used.
  explicit InterpolatedGrid(const ProbabilityGrid& grid) : grid_(grid) {}

  // The probability at p (submap frame) and, when `gradient` is not null, its gradient
  // (per metre).
  double Evaluate(const Vec2& p, Vec2* gradient) const;

 private:
  const ProbabilityGrid& grid_;
};

}  // namespace atlas
