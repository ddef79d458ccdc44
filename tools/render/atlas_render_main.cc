// atlas-render: draws a simulated run (atlas-sim output directory) to PNG and/or SVG.

#include <cstdio>
#include <cstdlib>
#include <string>

#include "tools/render/canvas.h"
#include "tools/render/run_data.h"
#include "tools/render/run_drawing.h"

namespace {

constexpr const char* kUsage = R"(usage: atlas-render --run DIR [--png FILE] [--svg FILE] [options]

Draws an atlas-sim output directory (world.txt, truth.tsv, run.clf): the walls, the true
trajectory, the odometry trajectory (started at the true start pose), laser returns of a
thinned-out set of scans placed at the true poses, start and end, a legend and a scale bar.
With neither --png nor --svg, writes DIR/run.png.

options:
  --run DIR          the atlas-sim output directory to draw
  --png FILE         write a PNG picture
  --svg FILE         write an SVG picture
  --width PX         picture width in pixels (default 1600); the height follows the building
  --scans N          draw about N scans, evenly spread over the run (default 400; 0 = none)
  --no-odometry      do not draw the odometry trajectory
  --odometry-km X    draw the odometry of the first X km only (default 1; 0 = all)
  --fit-odometry     fit the view to the odometry too (by default it is clipped to the world)
  --route-graph      draw the world's route graph (dashed green)
  --title TEXT       title line (default: a summary of the run)
  --help             this text
)";

int Fail(const std::string& message) {
  std::fprintf(stderr, "atlas-render: %s\n(atlas-render --help for usage)\n", message.c_str());
  return 2;
}

}  // namespace

int main(int argc, char** argv) {
  using namespace atlas::draw;
  std::string dir, png, svg;
  RunDrawOptions draw;
  RunReadOptions read;
  read.max_scans = 400;
  for (int i = 1; i < argc; ++i) {
    const std::string a = argv[i];
    if (a == "--help" || a == "-h") {
      std::fputs(kUsage, stdout);
      return 0;
    }
    if (a == "--no-odometry") {
      draw.draw_odometry = false;
      continue;
    }
    if (a == "--fit-odometry") {
      draw.fit_odometry = true;
      continue;
    }
    if (a == "--route-graph") {
      draw.draw_route_graph = true;
      continue;
    }
    if (a != "--run" && a != "--png" && a != "--svg" && a != "--width" && a != "--scans" &&
        a != "--odometry-km" && a != "--title")
      return Fail("unknown option '" + a + "'");
    if (i + 1 >= argc) return Fail("option " + a + " needs a value");
    const std::string v = argv[++i];
    auto integer = [&](long lo, long hi) {
      char* end = nullptr;
      const long x = std::strtol(v.c_str(), &end, 10);
      if (end == v.c_str() || *end != '\0' || x < lo || x > hi) {
        std::fprintf(stderr, "atlas-render: %s: '%s' is not an integer in [%ld, %ld]\n", a.c_str(),
                     v.c_str(), lo, hi);
        std::exit(2);
      }
      return x;
    };
    if (a == "--run") {
      dir = v;
    } else if (a == "--png") {
      png = v;
    } else if (a == "--svg") {
      svg = v;
    } else if (a == "--width") {
      draw.width_px = static_cast<int>(integer(200, 20000));
    } else if (a == "--scans") {
      read.max_scans = integer(0, 1000000);
    } else if (a == "--odometry-km") {
      char* end = nullptr;
      const double km = std::strtod(v.c_str(), &end);
      if (end == v.c_str() || *end != '\0' || !(km >= 0.0 && km <= 1e6))
        return Fail("--odometry-km: '" + v + "' is not a distance in km (0 = all)");
      draw.odometry_length_m = 1000.0 * km;
    } else if (a == "--title") {
      draw.title = v;
    }
  }
  if (dir.empty()) return Fail("--run DIR is required (an atlas-sim output directory)");
  if (png.empty() && svg.empty()) png = dir + "/run.png";
  draw.draw_scans = read.max_scans > 0;

  RunData run;
  if (const std::string e = ReadRun(dir, read, &run); !e.empty()) return Fail(e);
  struct ReleaseAtExit {
    ~ReleaseAtExit() { ReleaseDrawingCaches(); }
  } release_at_exit;
  int height = 0;
  ViewTransform view;
  LayoutRun(run, draw, &height, &view);
  for (const auto& [path, format] :
       {std::pair{png, ImageFormat::kPng}, std::pair{svg, ImageFormat::kSvg}}) {
    if (path.empty()) continue;
    std::string error;
    auto canvas = Canvas::Create(format, path, draw.width_px, height, view, &error);
    if (!canvas) return Fail(error);
    DrawRun(*canvas, run, draw);
    if (error = canvas->Finish(); !error.empty()) return Fail(error);
    std::fprintf(stderr, "atlas-render: wrote %s (%d x %d px, %.1f px/m)\n", path.c_str(),
                 draw.width_px, height, view.pixels_per_metre());
  }
  return 0;
}
