#include "core/grid/discrete_scans.h"

#include <algorithm>
#include <cmath>
#include <cstdlib>

namespace atlas {

double AngularSearchStep(const std::vector<Vec2>& points, double resolution, double min_step) {
  double max_squared = 0.0;
  for (const Vec2& p : points) max_squared = std::max(max_squared, p.squaredNorm());
  if (max_squared <= resolution * resolution) return std::max(min_step, 1.0);
  const double step = std::acos(1.0 - resolution * resolution / (2.0 * max_squared));
  return std::max(step, min_step);
}

SearchWindow MakeSearchWindow(double linear, double angular, double resolution,
                              double angular_step) {
  SearchWindow w;
  w.linear_cells = static_cast<int>(std::ceil(linear / resolution - 1e-9));
  w.angular_steps = static_cast<int>(std::ceil(angular / angular_step - 1e-9));
  w.angular_step = angular_step;
  return w;
}

Pose2 PlacementPose(const Placement& placement, const Pose2& center, const SearchWindow& window,
                    double resolution) {
  return Pose2{
      center.x + placement.x * resolution, center.y + placement.y * resolution,
      WrapAngle(center.theta + (placement.heading - window.angular_steps) * window.angular_step)};
}

void DiscretizeScans(const GridLimits& limits, const std::vector<Vec2>& points, const Pose2& center,
                     const SearchWindow& window, DiscreteScans* out) {
  out->points = static_cast<int>(points.size());
  out->cells.resize(static_cast<size_t>(window.headings()) * points.size());
  CellIndex* cell = out->cells.data();
  for (int h = 0; h < window.headings(); ++h) {
    const RigidTransform t(PlacementPose(Placement{h, 0, 0}, center, window, limits.resolution));
    for (const Vec2& p : points) *cell++ = limits.CellOf(t.Apply(p));
  }
}

bool Peak::Contains(const Placement& p) const {
  return std::abs(p.heading - best.heading) <= steps && std::abs(p.x - best.x) <= cells &&
         std::abs(p.y - best.y) <= cells;
}

bool Peak::ContainsBlock(const Placement& p, int width) const {
  return std::abs(p.heading - best.heading) <= steps && p.x >= best.x - cells &&
         p.x + width - 1 <= best.x + cells && p.y >= best.y - cells &&
         p.y + width - 1 <= best.y + cells;
}

Peak MakePeak(const Placement& best, double distance, double angle, double resolution,
              const SearchWindow& window) {
  Peak peak;
  peak.best = best;
  peak.cells = static_cast<int>(std::floor(distance / resolution + 1e-9));
  peak.steps = static_cast<int>(std::floor(angle / window.angular_step + 1e-9));
  return peak;
}

}  // namespace atlas
