#include "core/grid/interpolated_grid.h"

#include <cmath>

namespace atlas {
namespace {

// Catmull-Rom cubic through p1 (t = 0) and p2 (t = 1); its derivative in `slope`.
double CatmullRom(double p0, double p1, double p2, double p3, double t, double* slope) {
  const double a = 0.5 * (-p0 + 3.0 * p1 - 3.0 * p2 + p3);
  const double b = 0.5 * (2.0 * p0 - 5.0 * p1 + 4.0 * p2 - p3);
  const double c = 0.5 * (p2 - p0);
  *slope = (3.0 * a * t + 2.0 * b) * t + c;
  return ((a * t + b) * t + c) * t + p1;
}

}  // namespace

double InterpolatedGrid::Evaluate(const Vec2& p, Vec2* gradient) const {
  const GridLimits& l = grid_.limits();
  // Cell-centre coordinates: integer u is the centre of storage cell u.
  const Vec2 u = l.CellCoordinates(p) - Vec2(0.5, 0.5);
  const int ix = static_cast<int>(std::floor(u.x())), iy = static_cast<int>(std::floor(u.y()));
  const double tx = u.x() - ix, ty = u.y() - iy;
  double rows[4], row_slopes[4];
  for (int j = 0; j < 4; ++j) {
    double v[4];
    for (int i = 0; i < 4; ++i) v[i] = grid_.Probability(CellIndex{ix - 1 + i, iy - 1 + j});
    rows[j] = CatmullRom(v[0], v[1], v[2], v[3], tx, &row_slopes[j]);
  }
  double dy = 0.0, unused = 0.0;
  const double value = CatmullRom(rows[0], rows[1], rows[2], rows[3], ty, &dy);
  if (gradient != nullptr) {
    const double dx =
        CatmullRom(row_slopes[0], row_slopes[1], row_slopes[2], row_slopes[3], ty, &unused);
    *gradient = Vec2(dx, dy) / l.resolution;
  }
  return value;
}

}  // namespace atlas
