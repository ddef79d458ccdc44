// atlas-export: an atlas (atlas-replay's output, or what atlasd --export-atlas writes) in the
// formats other tools read. See --help.

#include <cstdio>
#include <filesystem>
#include <optional>
#include <string>

#include "formats/replay_dir.h"
#include "formats/text_rows.h"
#include "tools/cli/command_line.h"
#include "tools/export/export_files.h"

namespace atlas::exporter {
namespace {

constexpr const char* kDescription =
    R"(Writes the atlas in DIR (an atlas-replay output directory, or what atlasd --export-atlas
writes: graph.tsv, points.tsv, and trajectory.tsv when present) in the formats other tools
read, every frame placed by the Dijkstra projection from the reference frame:

  OUT/atlas.g2o       VERTEX_SE2 per placed frame, EDGE_SE2 per edge with its information
                      matrix (inverse covariance), FIX of the reference frame
  OUT/trajectory.tum  the trajectory (timestamp tx ty tz qx qy qz qw) in the reference
                      frame; only when DIR has trajectory.tsv
  OUT/points.ply      the laser points each frame keeps, placed (ASCII PLY)
  OUT/map.pgm         occupancy grid in ROS map_server's layout: the cells holding a point
  OUT/map.yaml        occupied (black), every other cell unknown (grey); no free space, as
                      the kept points do not say where they were seen from)";

constexpr const char* kFooter =
    R"(Frames the projection does not reach (another component of the graph) are left out with what
they hold, and counted on stderr. docs/formats.md describes every file.

Exit status: 0 written, 1 bad input or a file that cannot be written, 2 bad command line.
)";

int Main(int argc, char** argv) {
  std::string dir, out;
  ExportOptions options;
  cli::CommandLine command_line("atlas-export", {"atlas-export [options] DIR"}, kDescription,
                                kFooter);
  CLI::App& app = command_line.app();
  cli::AddPositional(app, "DIR", &dir, "an atlas-replay output directory");
  cli::AddText(app, "--out", "OUT", &out, "output directory (default DIR/export; made if missing)");
  cli::AddInteger(app, "--reference", "F", 0, 100000000, &options.reference,
                  "the frame the others are placed in (default " +
                      std::to_string(ExportOptions{}.reference) + ")");
  cli::AddNumber(app, "--resolution", "M", 0.01, 10, &options.resolution_m,
                 "occupancy grid cell, metres (0.01 to 10; default " +
                     cli::HelpNumber(ExportOptions{}.resolution_m) +
                     ", the kept\n"
                     "points' cell)");
  if (std::optional<int> done = command_line.Parse(argc, argv)) return *done;
  if (dir.empty()) return command_line.Usage("no DIR given (an atlas-replay output directory)");
  if (out.empty()) out = dir + "/export";

  formats::ReplayFilesWanted wanted;
  wanted.trajectory = false;
  formats::ReplayOutput run;
  if (std::string e = formats::ReadReplayOutput(dir, wanted, &run); !e.empty()) {
    std::fprintf(stderr, "atlas-export: %s\n", e.c_str());
    return 1;
  }
  ExportFiles files;
  if (std::string e = MakeExportFiles(run, options, "map.pgm", &files); !e.empty()) {
    std::fprintf(stderr, "atlas-export: %s: %s\n", dir.c_str(), e.c_str());
    return 1;
  }
  std::error_code ec;
  std::filesystem::create_directories(out, ec);
  if (ec) {
    std::fprintf(stderr, "atlas-export: cannot create %s: %s\n", out.c_str(), ec.message().c_str());
    return 1;
  }
  const auto write = [&](const char* name, const std::string& text, const std::string& what) {
    const std::string path = out + "/" + name;
    if (std::string e = formats::WriteTextFile(path, text); !e.empty()) {
      std::fprintf(stderr, "atlas-export: %s\n", e.c_str());
      return false;
    }
    std::printf("wrote %s (%s)\n", path.c_str(), what.c_str());
    return true;
  };
  const auto n = [](int v) { return std::to_string(v); };
  if (!write("atlas.g2o", files.g2o,
             n(files.placed_frames) + " vertices, " + n(files.edges_written) + " edges"))
    return 1;
  if (files.has_trajectory &&
      !write("trajectory.tum", files.tum, n(files.trajectory_written) + " poses"))
    return 1;
  if (files.has_points) {
    if (!write("points.ply", files.ply, n(files.points_written) + " points") ||
        !write("map.pgm", files.pgm,
               n(files.grid_width) + " x " + n(files.grid_height) + " cells, " +
                   n(files.occupied_cells) + " occupied") ||
        !write("map.yaml", files.yaml, "map_server"))
      return 1;
  }
  if (!files.has_trajectory)
    std::fprintf(stderr, "atlas-export: %s has no trajectory.tsv rows: no trajectory.tum\n",
                 dir.c_str());
  if (!files.has_points)
    std::fprintf(stderr,
                 "atlas-export: no placed laser points (%s/points.tsv missing or empty): "
                 "no points.ply, map.pgm, map.yaml\n",
                 dir.c_str());
  if (files.placed_frames < files.frames)
    std::fprintf(stderr,
                 "atlas-export: warning: %d of %d frames are not connected to frame %d and are "
                 "left out: %d of %d edges, %d of %d trajectory rows, %d of %d points\n",
                 files.frames - files.placed_frames, files.frames, options.reference,
                 files.edges - files.edges_written, files.edges,
                 files.trajectory_rows - files.trajectory_written, files.trajectory_rows,
                 files.points - files.points_written, files.points);
  return 0;
}

}  // namespace
}  // namespace atlas::exporter

int main(int argc, char** argv) { return atlas::exporter::Main(argc, argv); }
