// atlas-render: draws a simulated run (atlas-sim output directory) or an atlas (atlas-replay
// output directory) to PNG and/or SVG.

#include <cstdio>
#include <limits>
#include <optional>
#include <string>

#include "core/eval/atlas_relations.h"
#include "tools/cli/command_line.h"
#include "tools/refine/global_refinement.h"
#include "tools/render/atlas_drawing.h"
#include "tools/render/canvas.h"
#include "tools/render/run_data.h"
#include "tools/render/run_drawing.h"

namespace {

constexpr const char* kDescription =
    R"(Draws an atlas-sim output directory (--run DIR: world.txt, truth.tsv, run.clf): the walls, the
true trajectory, the odometry trajectory (started at the true start pose), laser returns of a
thinned-out set of scans placed at the true poses, start and end, a legend and a scale bar.
With neither --png nor --svg, writes DIR/run.png.
Or draws an atlas-replay output directory (--atlas DIR: graph.tsv, maps.tsv, points.tsv,
trajectory.tsv, global.tsv, timing.tsv; docs/formats.md) as one of the pictures below. An atlas
of grid frames (localmap.kind = "grid") has no lines: its map is drawn from points.tsv, the
frames' occupied cells.)";

constexpr const char* kFooter =
    R"(Input files are checked as they are read: a malformed line (also in run.clf: a line that is
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
      !e.empty()) {
    std::fprintf(stderr, "atlas-render: --projection: %s\nTry 'atlas-render --help'.\n", e.c_str());
    return atlas::cli::kExitUsage;
  }
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
  atlas::cli::CommandLine command_line(
      "atlas-render",
      {"atlas-render --run DIR [--png FILE] [--svg FILE] [options]",
       "atlas-render --atlas DIR [--projection F | --whole | --timeline | --timeline-frames]",
       "             [--png FILE] [--svg FILE] [options]"},
      kDescription, kFooter);
  CLI::App& app = command_line.app();
  namespace cli = atlas::cli;
  const std::string atlas_group = "An atlas (--atlas DIR)";
  cli::AddText(app, "--atlas", "DIR", &atlas_req.dir, "the atlas-replay output directory to draw")
      .Group(atlas_group);
  cli::AddInteger(app, "--projection", "F", 0, std::numeric_limits<atlas::FrameId>::max(),
                  &atlas_req.draw.source,
                  "the Dijkstra projection from frame F (default 0): every reached frame's\n"
                  "lines and points (points.tsv, if there: the laser points it keeps, or\n"
                  "a grid frame's occupied cells) at its projected pose, its origin and\n"
                  "3-sigma position ellipse, the projection tree (paper, Fig. 2 and 10).\n"
                  "Default file DIR/projection-F.png")
      .Group(atlas_group);
  bool whole = false, timeline = false, timeline_frames = false;
  cli::AddFlag(app, "--whole", &whole,
               "the whole run: every frame from frame 0 and the robot's global trajectory\n"
               "(Fig. 8). Default file DIR/whole.png")
      .Group(atlas_group);
  cli::AddFlag(app, "--refined", &atlas_req.draw.refined,
               "with --whole or --projection: frames placed by global least squares\n"
               "(the same refinement as atlas-replay --refine) instead of the projection")
      .Group(atlas_group);
  cli::AddFlag(app, "--timeline", &timeline,
               "step time and the dominant frame id over time (Fig. 7); DIR/timeline.png")
      .Group(atlas_group);
  cli::AddFlag(app, "--timeline-frames", &timeline_frames,
               "step time against the number of frames; DIR/timeline-frames.png")
      .Group(atlas_group);
  cli::AddNumber(app, "--budget", "MS", 0, 1e9, &atlas_req.budget_ms,
                 "step budget drawn on the timelines (default 10)")
      .Group(atlas_group);
  cli::AddFlag(app, "--cpu", &atlas_req.cpu,
               "timelines: plot each step's CPU time (step_cpu.tsv) instead of its wall\n"
               "time (on a shared machine wall time includes other processes' turns)")
      .Group(atlas_group);
  bool no_ellipses = false, no_labels = false;
  cli::AddFlag(app, "--no-ellipses", &no_ellipses, "no uncertainty ellipses").Group(atlas_group);
  cli::AddFlag(app, "--no-labels", &no_labels, "no frame ids").Group(atlas_group);
  cli::AddText(app, "--run", "DIR", &dir, "the atlas-sim output directory to draw");
  cli::AddText(app, "--png", "FILE", &png, "write a PNG picture");
  cli::AddText(app, "--svg", "FILE", &svg, "write an SVG picture");
  cli::AddInteger(app, "--width", "PX", 200, 20000, &draw.width_px,
                  "picture width in pixels (default 1600); the height follows the building");
  cli::AddInteger(app, "--scans", "N", 0, 1000000, &read.max_scans,
                  "draw about N scans, evenly spread over the run (default 400; 0 = none)");
  bool no_odometry = false;
  cli::AddFlag(app, "--no-odometry", &no_odometry, "do not draw the odometry trajectory");
  cli::AddNumber(
      app, "--odometry-km", "X", 0, 1e6, [&](double km) { draw.odometry_length_m = 1000.0 * km; },
      "draw the odometry of the first X km only (default 1; 0 = all)");
  cli::AddFlag(app, "--fit-odometry", &draw.fit_odometry,
               "fit the view to the odometry too (by default it is clipped to the world)");
  cli::AddFlag(app, "--route-graph", &draw.draw_route_graph,
               "draw the world's route graph (dashed green)");
  cli::AddText(app, "--title", "TEXT", &draw.title, "title line (default: a summary of the run)");
  if (std::optional<int> done = command_line.Parse(argc, argv)) return *done;
  auto Usage = [&](const std::string& what) { return command_line.Usage(what); };
  if (whole + timeline + timeline_frames > 1 ||
      ((whole || timeline || timeline_frames) && cli::Given(app, "--projection")))
    return Usage(
        "--projection, --whole, --timeline and --timeline-frames are different pictures: "
        "give one");
  if (whole) {
    atlas_req.picture = AtlasPicture::kWhole;
    atlas_req.draw.trajectory = true;
    atlas_req.draw.ellipses = false;
    atlas_req.draw.source = 0;
  }
  if (timeline) atlas_req.picture = AtlasPicture::kTimeline;
  if (timeline_frames) atlas_req.picture = AtlasPicture::kTimelineFrames;
  if (no_ellipses) atlas_req.draw.ellipses = false;
  if (no_labels) atlas_req.draw.frame_labels = false;
  if (no_odometry) draw.draw_odometry = false;
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
