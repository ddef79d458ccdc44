#include "tools/export/export_files.h"

#include "core/atlas/dijkstra_projection.h"
#include "core/eval/atlas_relations.h"
#include "formats/g2o.h"
#include "formats/occupancy_grid.h"
#include "formats/ply_points.h"
#include "formats/tum_trajectory.h"

namespace atlas::exporter {

std::string ExportOptions::Validate() const {
  if (reference < 0) return "the reference frame must be a frame id (0 or more)";
  if (!(resolution_m >= 0.01 && resolution_m <= 10.0)) return "the resolution must be 0.01 to 10 m";
  if (!(margin_m >= 0.0 && margin_m <= 100.0)) return "the margin must be 0 to 100 m";
  return "";
}

std::string MakeExportFiles(const formats::ReplayOutput& run, const ExportOptions& options,
                            const std::string& pgm_name, ExportFiles* out) {
  *out = ExportFiles{};
  if (std::string e = options.Validate(); !e.empty()) return e;
  if (options.reference >= run.frame_count)
    return "the atlas has " + std::to_string(run.frame_count) + " frames (0.." +
           std::to_string(run.frame_count - 1) + "), no frame " + std::to_string(options.reference);
  AtlasGraph graph;
  if (std::string e = eval::BuildGraphFromEdges(run.frame_count, run.graph.edges, &graph);
      !e.empty())
    return "graph.tsv: " + e;
  const std::vector<std::optional<Pose2>> placed =
      formats::FramePosesFrom(graph, options.reference);
  const auto place = [&](FrameId f) -> const std::optional<Pose2>* {
    return f >= 0 && static_cast<size_t>(f) < placed.size() && placed[f] ? &placed[f] : nullptr;
  };
  const std::string from = "frames placed from frame " + std::to_string(options.reference) +
                           " by the Dijkstra projection";
  out->frames = run.frame_count;

  formats::G2oGraph g2o;
  for (FrameId f = 0; f < graph.FrameCount(); ++f)
    if (const auto* p = place(f)) g2o.vertices.push_back({f, **p});
  out->placed_frames = static_cast<int>(g2o.vertices.size());
  out->edges = static_cast<int>(run.graph.edges.size());
  for (const eval::EdgeRow& e : run.graph.edges) {
    if (place(e.from) == nullptr || place(e.to) == nullptr) continue;
    formats::G2oEdge edge{e.from, e.to, e.to_in_from.mean, Mat3::Identity()};
    // graph.tsv's reader refused covariances that are not positive definite.
    const bool invertible = formats::InformationOf(e.to_in_from.cov, &edge.information);
    if (!invertible) return "graph.tsv: the covariance of an edge has no inverse";
    g2o.edges.push_back(edge);
  }
  g2o.fixed.push_back(options.reference);
  out->edges_written = static_cast<int>(g2o.edges.size());
  out->g2o = formats::FormatG2o(g2o, "atlas-export: " + from + "; edges with information");

  out->trajectory_rows = static_cast<int>(run.trajectory.size());
  out->has_trajectory = !run.trajectory.empty();
  if (out->has_trajectory) {
    const std::vector<eval::TimedPose> poses = formats::PlaceTrajectory(run.trajectory, placed);
    out->trajectory_written = static_cast<int>(poses.size());
    out->tum = formats::FormatTumTrajectory(
        poses, "atlas-export: timestamp tx ty tz qx qy qz qw; " + from);
  }

  std::vector<formats::PlyPoint> cloud;
  std::vector<Vec2> points;
  out->points = static_cast<int>(run.points.size());
  for (const formats::FramePointRow& r : run.points) {
    const auto* p = place(r.frame);
    if (p == nullptr) continue;
    const Vec2 q = (*p)->TransformPoint(r.p);
    cloud.push_back({q, r.frame});
    points.push_back(q);
  }
  out->points_written = static_cast<int>(points.size());
  out->has_points = !points.empty();
  if (!out->has_points) return "";
  out->ply = formats::FormatPlyPoints(cloud, "atlas-export: kept laser points; " + from);
  const formats::OccupancyGrid grid =
      formats::OccupiedCellsGrid(points, options.resolution_m, options.margin_m);
  out->grid_width = grid.width;
  out->grid_height = grid.height;
  for (formats::Occupancy c : grid.cells) out->occupied_cells += c == formats::Occupancy::kOccupied;
  out->pgm = formats::FormatPgm(
      grid, "atlas-export: occupied cells of the kept laser points (no free space); " + from);
  out->yaml = formats::FormatMapYaml(grid, pgm_name);
  return "";
}

}  // namespace atlas::exporter
