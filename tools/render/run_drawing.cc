#include "tools/render/run_drawing.h"

#include <algorithm>
#include <cmath>

namespace atlas::draw {
namespace {

constexpr double kHeaderPx = 56.0;
constexpr double kMarginPx = 24.0;
const Color kWallColor{0.25, 0.25, 0.28};
const Color kTruthColor{0.12, 0.35, 0.85, 0.55};
const Color kOdometryColor{0.85, 0.1, 0.55, 0.7};
const Color kScanColor{1.0, 0.45, 0.0, 0.6};
const Color kGraphColor{0.2, 0.7, 0.3, 0.6};
const Color kGlassColor{0.3, 0.75, 0.95};
const Color kPeopleColor{0.6, 0.2, 0.8, 0.5};

sim::Bounds ContentBounds(const RunData& run, bool with_odometry) {
  sim::Bounds b = sim::WorldBounds(run.world);
  for (const TruthSample& t : run.truth) b.Extend(Vec2(t.pose.x, t.pose.y));
  if (with_odometry || b.empty)
    for (const OdometrySample& o : run.odometry) b.Extend(Vec2(o.pose.x, o.pose.y));
  if (b.empty) b.Extend(Vec2::Zero());
  return b;
}

// Odometry expressed in the truth's frame: the odometry frame's origin is put on the true
// start pose, so both trajectories start together.
Pose2 OdometryToWorld(const RunData& run) {
  if (run.truth.empty() || run.odometry.empty()) return Pose2{};
  return Compose(run.truth.front().pose, Inverse(run.odometry.front().pose));
}

}  // namespace

void LayoutRun(const RunData& run, const RunDrawOptions& options, int* height_px,
               ViewTransform* view) {
  const sim::Bounds b = ContentBounds(run, options.fit_odometry);
  const Vec2 size = (b.max - b.min).cwiseMax(Vec2(1.0, 1.0));
  const double map_w = options.width_px - 2 * kMarginPx;
  const double scale = map_w / size.x();
  const double map_h = std::clamp(scale * size.y(), 200.0, 4.0 * options.width_px);
  *height_px = static_cast<int>(std::ceil(kHeaderPx + map_h + 2 * kMarginPx));
  *view = ViewTransform::Fit(b.min, b.max, kMarginPx, kHeaderPx + kMarginPx, map_w, map_h);
}

void DrawRun(Canvas& canvas, const RunData& run, const RunDrawOptions& options) {
  const double px_per_m = canvas.view().pixels_per_metre();
  std::vector<std::pair<Vec2, Vec2>> walls, glass;
  for (const sim::Wall& w : run.world.walls) (w.glass ? glass : walls).emplace_back(w.a, w.b);
  canvas.Segments(walls, Stroke{kWallColor, std::clamp(0.06 * px_per_m, 1.0, 3.0)});
  if (!glass.empty())
    canvas.Segments(glass, Stroke{kGlassColor, std::clamp(0.06 * px_per_m, 1.0, 3.0)});
  // People: the paths they walk to and fro.
  std::vector<std::pair<Vec2, Vec2>> walks;
  for (const sim::Person& p : run.world.people) walks.emplace_back(p.a, p.b);
  if (!walks.empty())
    canvas.Segments(walks, Stroke{kPeopleColor, std::clamp(0.1 * px_per_m, 1.5, 5.0)});
  // Scans over the walls they hit (the walls stay visible around them).
  if (options.draw_scans) {
    std::vector<Vec2> points;
    for (const RunScan& s : run.scans) {
      const Pose2 robot = run.truth.empty() ? Compose(OdometryToWorld(run), s.robot_odometry)
                                            : InterpolateTruth(run.truth, s.stamp);
      const Pose2 laser = Compose(robot, Between(s.robot_odometry, s.laser_in_odometry));
      const std::vector<Vec2> p = ScanPoints(s, laser);
      points.insert(points.end(), p.begin(), p.end());
    }
    canvas.Points(points, kScanColor, std::clamp(0.06 * px_per_m, 0.7, 2.0));
  }
  if (options.draw_route_graph) {
    std::vector<std::pair<Vec2, Vec2>> edges;
    for (const sim::RouteEdge& e : run.world.edges)
      edges.emplace_back(run.world.nodes[e.from].position, run.world.nodes[e.to].position);
    canvas.Segments(edges, Stroke{kGraphColor, 1.0, true});
  }
  if (options.draw_odometry && !run.odometry.empty()) {
    const Pose2 to_world = OdometryToWorld(run);
    std::vector<Vec2> line;
    line.reserve(run.odometry.size());
    double length = 0.0;
    for (const OdometrySample& o : run.odometry) {
      const Pose2 p = Compose(to_world, o.pose);
      if (!line.empty()) length += (Vec2(p.x, p.y) - line.back()).norm();
      if (options.odometry_length_m > 0.0 && length > options.odometry_length_m) break;
      line.emplace_back(p.x, p.y);
    }
    canvas.Polyline(line, Stroke{kOdometryColor, 1.2});
  }
  if (!run.truth.empty()) {
    std::vector<Vec2> line;
    line.reserve(run.truth.size());
    for (const TruthSample& t : run.truth) line.emplace_back(t.pose.x, t.pose.y);
    canvas.Polyline(line, Stroke{kTruthColor, 1.6});
    const double marker_m = 5.0 / px_per_m;  // 5 px at any scale
    canvas.Pose(run.truth.front().pose, marker_m, Color{0.1, 0.6, 0.2});
    canvas.Pose(run.truth.back().pose, marker_m, Color{0.8, 0.1, 0.1});
  }

  // Header: title, then legend.
  canvas.FillRectPx(0, 0, canvas.width_px(), kHeaderPx, Color{0.96, 0.96, 0.96});
  std::string title = options.title;
  if (title.empty()) {
    double length = 0.0;
    for (size_t i = 1; i < run.truth.size(); ++i)
      length += std::hypot(run.truth[i].pose.x - run.truth[i - 1].pose.x,
                           run.truth[i].pose.y - run.truth[i - 1].pose.y);
    char buf[256];
    std::snprintf(buf, sizeof(buf),
                  "simulated run: %.2f km, %.0f min, %d rooms, %zu walls; %ld scans (every "
                  "%ld-th drawn)",
                  length / 1000.0,
                  run.truth.empty()
                      ? 0.0
                      : ToSeconds(run.truth.back().stamp - run.truth.front().stamp) / 60.0,
                  run.world.CountNodes(sim::NodeKind::kRoom), run.world.walls.size(),
                  run.total_scans, run.scan_stride);
    title = buf;
  }
  canvas.TextPx(Vec2(kMarginPx, 22), title, 16, Color{0, 0, 0}, true);
  std::vector<LegendEntry> legend{{"walls", kWallColor}, {"true trajectory", kTruthColor}};
  if (!glass.empty()) legend.push_back({"glass (no return)", kGlassColor});
  if (!walks.empty()) legend.push_back({"people walking", kPeopleColor});
  std::string odometry_label = "odometry (drifts)";
  if (options.odometry_length_m > 0.0) {
    char buf[64];
    std::snprintf(buf, sizeof(buf), "odometry, first %.1f km (drifts)",
                  options.odometry_length_m / 1000.0);
    odometry_label = buf;
  }
  if (options.draw_odometry && !run.odometry.empty())
    legend.push_back({odometry_label, kOdometryColor});
  if (options.draw_scans && !run.scans.empty())
    legend.push_back({"laser returns", kScanColor, true});
  legend.push_back({"start", Color{0.1, 0.6, 0.2}, true});
  legend.push_back({"end", Color{0.8, 0.1, 0.1}, true});
  canvas.Legend(Vec2(kMarginPx, 46), legend);
  canvas.ScaleBar();
}

}  // namespace atlas::draw
