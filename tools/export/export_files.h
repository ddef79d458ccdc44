#pragma once
// The files atlas-export writes from an atlas-replay output directory (docs/formats.md,
// "Exported files"), made in memory: every frame placed by the Dijkstra projection from the
// reference frame (paper, Section III-A: the pose of each frame in the reference frame along
// the path of least det(covariance), eq. 2-3), then
// - g2o: a VERTEX_SE2 per placed frame, an EDGE_SE2 per edge between placed frames with its
//   information matrix, and FIX of the reference frame (formats/g2o.h);
// - TUM: the trajectory rows composed with their frame's placement (formats/tum_trajectory.h);
// - PLY: each frame's kept laser points placed (formats/ply_points.h);
// - PGM + YAML: the cells holding a placed point occupied, every other cell unknown
//   (formats/occupancy_grid.h). No free space: the kept points are cells without the poses they
//   were seen from, so no ray can be cast.
// Frames the projection does not reach (another component of the graph) and what they hold are
// left out and counted.

#include <string>
#include <vector>

#include "formats/replay_dir.h"

namespace atlas::exporter {

struct ExportOptions {
  FrameId reference = 0;
  double resolution_m = 0.1;  // the occupancy grid's cell (the kept points are 10 cm cells)
  double margin_m = 1.0;      // unknown cells around the points
  std::string Validate() const;
};

struct ExportFiles {
  std::string g2o, tum, ply, pgm, yaml;
  bool has_trajectory = false;  // false: the directory has no trajectory rows, tum is empty
  bool has_points = false;      // false: no placed points, ply/pgm/yaml are empty
  int frames = 0, placed_frames = 0;
  int edges = 0, edges_written = 0;
  int trajectory_rows = 0, trajectory_written = 0;
  int points = 0, points_written = 0;
  int grid_width = 0, grid_height = 0, occupied_cells = 0;
};

// "" or what is wrong (a reference frame the directory does not have, an edge list that does
// not make a graph). `pgm_name` is the image the YAML names.
std::string MakeExportFiles(const formats::ReplayOutput& run, const ExportOptions& options,
                            const std::string& pgm_name, ExportFiles* out);

}  // namespace atlas::exporter
