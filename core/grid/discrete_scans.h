#pragma once
// The discretised search space shared by the correlative matchers (Olson 2009, "Real-time
// correlative scan matching", Section III; Hess et al. 2016, Section V-A): a window of
// headings around a centre pose, in steps small enough that the farthest point moves by about
// one cell (Hess eq. 7), and of whole-cell translations. For each heading the points are
// rotated and binned once; a translation by (x, y) cells then moves every binned cell by
// (x, y), so a placement is scored with lookups only. No I/O.

#include <cstdint>
#include <vector>

#include "core/geometry/se2.h"
#include "core/grid/probability_grid.h"

namespace atlas {

// Hess et al. 2016, eq. 7: acos(1 - r^2 / (2 d_max^2)), d_max the farthest point's distance
// from the origin of `points`' frame; never below `min_step`.
double AngularSearchStep(const std::vector<Vec2>& points, double resolution, double min_step);

struct SearchWindow {
  int linear_cells = 0;       // x and y offsets in [-linear_cells, linear_cells]
  int angular_steps = 0;      // heading indices in [0, 2 angular_steps], centre at angular_steps
  double angular_step = 0.0;  // radians
  int headings() const { return 2 * angular_steps + 1; }
};

// The window covering `linear` metres and `angular` radians either side.
SearchWindow MakeSearchWindow(double linear, double angular, double resolution,
                              double angular_step);

// A placement in a window: heading index and translation in cells.
struct Placement {
  int heading = 0;
  int x = 0;
  int y = 0;
};

// The pose of `placement` in the window around `center`.
Pose2 PlacementPose(const Placement& placement, const Pose2& center, const SearchWindow& window,
                    double resolution);

// Points (in the frame of the pose being searched for) binned into `limits`' cells for every
// heading of `window` around `center`: cells[h * points + i] is point i at heading h.
struct DiscreteScans {
  int points = 0;
  std::vector<CellIndex> cells;
  const CellIndex* Heading(int h) const { return cells.data() + static_cast<size_t>(h) * points; }
};
void DiscretizeScans(const GridLimits& limits, const std::vector<Vec2>& points, const Pose2& center,
                     const SearchWindow& window, DiscreteScans* out);

// The placements around a best one that count as its peak (Condition 2: the runner-up is
// sought outside it): within `cells` cells on each axis and `steps` heading steps.
struct Peak {
  Placement best;
  int cells = 0;
  int steps = 0;
  bool Contains(const Placement& p) const;
  // Whether every placement of heading p.heading, x in [p.x, p.x + width), y in
  // [p.y, p.y + width) lies in the peak.
  bool ContainsBlock(const Placement& p, int width) const;
};
Peak MakePeak(const Placement& best, double distance, double angle, double resolution,
              const SearchWindow& window);

}  // namespace atlas
