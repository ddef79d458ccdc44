#pragma once
// Draws a simulated run: the building's walls, the true trajectory and the odometry (different
// colours), laser scans as points placed at the true pose, the robot at the end, a title,
// a legend and a scale bar.

#include <string>

#include "tools/render/canvas.h"
#include "tools/render/run_data.h"

namespace atlas::draw {

struct RunDrawOptions {
  int width_px = 1600;
  bool draw_odometry = true;
  // Draw the odometry of the first this many metres only (after that it has drifted far and
  // hides the rest); <= 0: all of it.
  double odometry_length_m = 1000.0;
  bool draw_scans = true;
  bool draw_route_graph = false;
  // Fit the view to the world and truth only (the odometry may drift far out and is clipped),
  // or to everything including the odometry.
  bool fit_odometry = false;
  std::string title;
};

// Image size and transform for `run`: width_px wide, a header band for title and legend.
void LayoutRun(const RunData& run, const RunDrawOptions& options, int* height_px,
               ViewTransform* view);

void DrawRun(Canvas& canvas, const RunData& run, const RunDrawOptions& options);

}  // namespace atlas::draw
