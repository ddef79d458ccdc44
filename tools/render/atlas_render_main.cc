// atlas-render: draws a simulated run (atlas-sim output directory) or an atlas (atlas-replay
// output directory) to PNG and/or SVG.

#include <cstdio>
#include <limits>
#include <string>

#include "core/common/parse_number.h"
#include "core/common/version.h"
#include "core/eval/atlas_relations.h"
#include "tools/refine/global_refinement.h"
#include "tools/render/atlas_drawing.h"
#include "tools/render/canvas.h"
#include "tools/render/run_data.h"
#include "tools/render/run_drawing.h"

namespace {

constexpr const char* kUsage = R"(usage: atlas-render --run DIR [--png FILE] [--svg FILE] [options]
       atlas-render --atlas DIR [--projection F | --whole | --timeline | --timeline-frames]
                    [--png FILE] [--svg FILE] [options]

--atlas DIR draws an atlas-replay output directory (graph.tsv, maps.tsv, points.tsv,
trajectory.tsv, global.tsv, timing.tsv; docs/formats.md):
  --projection F     the Dijkstra projection from frame F (default 0): every reached frame's
                     lines (and laser points, if points.tsv is there) at its projected
                     pose, its origin and 3-sigma position ellipse, the projection tree
                     (paper, Fig. 2 and 10). Default file DIR/projection-F.png
  --whole            the whole run: every frame from frame 0 and the robot's global trajectory
                     (Fig. 8). Default file DIR/whole.png
  --refined          with --whole or --projection: frames placed by global least squares
                     (the same refinement as atlas-replay --refine) instead of the projection
  --timeline         step time and the dominant frame id over time (Fig. 7); DIR/timeline.png
  --timeline-frames  step time against the number of frames; DIR/timeline-frames.png
  --budget MS        step budget drawn on the timelines (default 10)
  --cpu              timelines: plot each step's CPU time (step_cpu.tsv) instead of its wall
                     time (on a shared machine wall time includes other processes' turns)
  --no-ellipses      no uncertainty ellipses;  --no-labels: no frame ids

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
  --version          the version
  --help             this text

Input files are checked as they are read: a malformed line (also in run.clf: a line that is
not a CARMEN message, or a damaged ODOM/FLASER line), a missing or empty file the picture
needs, or files that disagree (an edge naming a frame the run does not have) is an error
naming the file and line.

Exit status: 0 written, 1 bad input file or the picture could not be written (message on
stderr), 2 bad command line.
)";

// Bad input files, or a picture that cannot be written: exit status 1.
int Fail(const std::string& message) {
  std::fprintf(stderr, "atlas-render: %s\n", message.c_str());
  return 1;
}

// A bad command line: exit status 2.
int Usage(const std::string& message) {
  std::fprintf(stderr, "atlas-render: %s\n(atlas-render --help for usage)\n", message.c_str());
  return 2;
}

enum class AtlasPicture { kProjection, kWhole, kTimeline, kTimelineFrames };

struct AtlasRequest {
  std::string dir, png, svg, title;
  AtlasPicture picture = AtlasPicture::kProjection;
  atlas::draw::AtlasDrawOptions draw;
  double budget_ms = 10.0;
  bool cpu = false;
};

// Writes `draw_fn` onto a PNG and/or SVG canvas of the given size and view.
template <typename F>
int WriteCanvases(const AtlasRequest& req, int width, int height,
                  const atlas::draw::ViewTransform& view, F&& draw_fn) {
  using namespace atlas::draw;
  for (const auto& [path, format] :
       {std::pair{req.png, ImageFormat::kPng}, std::pair{req.svg, ImageFormat::kSvg}}) {
    if (path.empty()) continue;
    std::string error;
    auto canvas = Canvas::Create(format, path, width, height, view, &error);
    if (!canvas) return Fail(error);
    draw_fn(*canvas);
    if (error = canvas->Finish(); !error.empty()) return Fail(error);
    std::fprintf(stderr, "atlas-render: wrote %s (%d x %d px)\n", path.c_str(), width, height);
  }
  return 0;
}

int RenderAtlas(AtlasRequest req) {
  using namespace atlas;
  using namespace atlas::draw;
  const bool timeline =
      req.picture == AtlasPicture::kTimeline || req.picture == AtlasPicture::kTimelineFrames;
  formats::ReplayFilesWanted wanted;
  wanted.timing = timeline;
  wanted.trajectory = !timeline;
  wanted.graph = !timeline;
  wanted.maps = !timeline;
  wanted.step_cpu = timeline && req.cpu;
  formats::ReplayOutput run;
  if (const std::string e = formats::ReadReplayOutput(req.dir, wanted, &run); !e.empty())
    return Fail(e);
  struct ReleaseAtExit {
    ~ReleaseAtExit() { ReleaseDrawingCaches(); }
  } release_at_exit;
  if (req.png.empty() && req.svg.empty()) {
    const char* names[] = {"projection", "whole", "timeline", "timeline-frames"};
    std::string name = names[static_cast<int>(req.picture)];
    if (req.picture == AtlasPicture::kProjection) name += "-" + std::to_string(req.draw.source);
    if (req.draw.refined) name += "-refined";
    req.png = req.dir + "/" + name + ".png";
  }
  if (timeline) {
    if (req.cpu) {
      for (formats::TimingRecord& r : run.timing)
        if (r.step >= 1 && r.step <= static_cast<int64_t>(run.step_cpu_ns.size()))
          r.step_ns = run.step_cpu_ns[static_cast<size_t>(r.step - 1)];
    }
    TimelineOptions t;
    t.width_px = req.draw.width_px;
    t.height_px = req.picture == AtlasPicture::kTimeline ? req.draw.width_px * 9 / 16
                                                         : req.draw.width_px * 5 / 12;
    t.axis = req.picture == AtlasPicture::kTimeline ? TimelineAxis::kTime : TimelineAxis::kFrames;
    t.budget_ms = req.budget_ms;
    t.step_label = req.cpu ? "step CPU time (ms)" : "step time (ms)";
    t.title =
        req.title.empty()
            ? (t.axis == TimelineAxis::kTime
                   ? "atlas-replay " + req.dir + ": step time and dominant map-frame over time"
                   : "atlas-replay " + req.dir + ": step time against the number of map-frames")
            : req.title;
    const ViewTransform view = ViewTransform::Fit(Vec2(0, 0), Vec2(t.width_px, t.height_px), 0, 0,
                                                  t.width_px, t.height_px);
    return WriteCanvases(req, t.width_px, t.height_px, view,
                         [&](Canvas& c) { DrawTimeline(c, run.timing, t); });
  }
  AtlasGraph graph;
  if (std::string e = eval::BuildGraphFromEdges(run.frame_count, run.graph.edges, &graph);
      !e.empty())
    return Fail(req.dir + "/graph.tsv: " + e);
  // Without global.tsv (an atlas exported from atlasd's store, with the poses it published:
  // scripts/demo.sh) the trajectory is placed as atlas-replay places it there.
  if (req.draw.trajectory && run.global.empty())
    run.global = formats::PlaceTrajectory(run.trajectory, formats::FramePosesFromFrameZero(graph));
  std::vector<std::optional<Pose2>> refined;
  if (req.draw.refined) {
    const refine::RefineResult r = refine::RefineGlobal(graph, refine::RefineOptions{});
    if (r.status == refine::RefineStatus::kFailed || r.status == refine::RefineStatus::kNoFrames)
      return Fail("global refinement: " + std::string(refine::ToString(r.status)) + " " +
                  r.message);
    refined = r.refined;
    if (r.skipped_edges > 0 || r.unreached > 0)
      std::fprintf(stderr,
                   "atlas-render: warning: refinement left out %d edges (covariance not usable) "
                   "and %d frames not connected to frame 0\n",
                   r.skipped_edges, r.unreached);
    if (req.draw.trajectory && run.refined.empty())
      run.refined = formats::PlaceTrajectory(run.trajectory, refined);
  }
  req.draw.title = req.title;
  AtlasLayout layout;
  int height = 0;
  ViewTransform view;
  if (const std::string e = LayoutAtlas(run, graph, req.draw, req.draw.refined ? &refined : nullptr,
                                        &layout, &height, &view);
      !e.empty())
    return Usage("--projection: " + e);
  return WriteCanvases(req, req.draw.width_px, height, view,
                       [&](Canvas& c) { DrawAtlasProjection(c, run, graph, layout, req.draw); });
}

}  // namespace

int main(int argc, char** argv) {
  using namespace atlas::draw;
  std::string dir, png, svg;
  RunDrawOptions draw;
  RunReadOptions read;
  read.max_scans = 400;
  AtlasRequest atlas_req;
  for (int i = 1; i < argc; ++i) {
    const std::string a = argv[i];
    if (a == "--version") {
      std::fputs(atlas::VersionLine("atlas-render").c_str(), stdout);
      return 0;
    }
    if (a == "--help" || a == "-h") {
      std::fputs(kUsage, stdout);
      return 0;
    }
    if (a == "--whole") {
      atlas_req.picture = AtlasPicture::kWhole;
      atlas_req.draw.trajectory = true;
      atlas_req.draw.ellipses = false;
      atlas_req.draw.source = 0;
      continue;
    }
    if (a == "--timeline" || a == "--timeline-frames") {
      atlas_req.picture =
          a == "--timeline" ? AtlasPicture::kTimeline : AtlasPicture::kTimelineFrames;
      continue;
    }
    if (a == "--cpu") {
      atlas_req.cpu = true;
      continue;
    }
    if (a == "--refined") {
      atlas_req.draw.refined = true;
      continue;
    }
    if (a == "--no-ellipses") {
      atlas_req.draw.ellipses = false;
      continue;
    }
    if (a == "--no-labels") {
      atlas_req.draw.frame_labels = false;
      continue;
    }
    if (a == "--atlas" || a == "--projection" || a == "--budget") {
      if (i + 1 >= argc) return Usage("option " + a + " needs a value");
      const std::string v = argv[++i];
      if (a == "--atlas") {
        atlas_req.dir = v;
        continue;
      }
      std::string error;
      if (a == "--budget") {
        if (!atlas::NumberArgument(a, v.c_str(), 0, 1e9, atlas_req.budget_ms, error))
          return Usage(error);
      } else {
        if (!atlas::IntegerArgument(a, v.c_str(), 0, std::numeric_limits<atlas::FrameId>::max(),
                                    atlas_req.draw.source, error))
          return Usage(error);
        atlas_req.picture = AtlasPicture::kProjection;
      }
      continue;
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
      return Usage("unknown option '" + a + "'");
    if (i + 1 >= argc) return Usage("option " + a + " needs a value");
    const std::string v = argv[++i];
    std::string error;
    if (a == "--run") {
      dir = v;
    } else if (a == "--png") {
      png = v;
    } else if (a == "--svg") {
      svg = v;
    } else if (a == "--width") {
      if (!atlas::IntegerArgument(a, v.c_str(), 200, 20000, draw.width_px, error))
        return Usage(error);
    } else if (a == "--scans") {
      if (!atlas::IntegerArgument(a, v.c_str(), 0, 1000000, read.max_scans, error))
        return Usage(error);
    } else if (a == "--odometry-km") {
      double km = 0.0;
      if (!atlas::NumberArgument(a, v.c_str(), 0, 1e6, km, error)) return Usage(error);
      draw.odometry_length_m = 1000.0 * km;
    } else if (a == "--title") {
      draw.title = v;
    }
  }
  if (!atlas_req.dir.empty()) {
    if (!dir.empty()) return Usage("give --run DIR or --atlas DIR, not both");
    atlas_req.png = png;
    atlas_req.svg = svg;
    atlas_req.title = draw.title;
    atlas_req.draw.width_px = draw.width_px;
    return RenderAtlas(atlas_req);
  }
  if (dir.empty())
    return Usage(
        "--run DIR (an atlas-sim output directory) or --atlas DIR (an atlas-replay "
        "output directory) is required");
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
