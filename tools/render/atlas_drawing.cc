#include "tools/render/atlas_drawing.h"

#include <algorithm>
#include <cmath>
#include <cstdio>

#include "core/atlas/dijkstra_projection.h"

namespace atlas::draw {
namespace {

constexpr double kHeaderPx = 56.0;
constexpr double kMarginPx = 24.0;
const Color kLineColor{0.1, 0.1, 0.12};
const Color kTreeColor{0.2, 0.55, 0.25, 0.8};
const Color kMatchColor{0.85, 0.15, 0.15, 0.7};
const Color kOtherEdgeColor{0.45, 0.45, 0.5, 0.6};
const Color kEllipseColor{0.15, 0.35, 0.85, 0.7};
const Color kTrajectoryColor{0.95, 0.55, 0.1, 0.6};
const Color kSourceColor{0.8, 0.1, 0.6};
const Color kPointColor{0.45, 0.6, 0.8, 0.7};

struct Box {
  Vec2 min = Vec2::Constant(std::numeric_limits<double>::infinity());
  Vec2 max = Vec2::Constant(-std::numeric_limits<double>::infinity());
  void Extend(const Vec2& p) {
    min = min.cwiseMin(p);
    max = max.cwiseMax(p);
  }
  bool empty() const { return !(min.x() <= max.x()); }
};

// The points of points.tsv whose frame the layout placed, in the layout's coordinates.
std::vector<Vec2> PlacedPoints(const std::vector<formats::FramePointRow>& rows,
                               const std::vector<std::optional<UncertainPose>>& frame_pose) {
  std::vector<Vec2> out;
  out.reserve(rows.size());
  for (const formats::FramePointRow& r : rows) {
    if (r.frame < 0 || r.frame >= static_cast<int>(frame_pose.size())) continue;
    const std::optional<UncertainPose>& pose = frame_pose[static_cast<size_t>(r.frame)];
    if (pose) out.push_back(pose->mean.TransformPoint(r.p));
  }
  return out;
}

std::string Fmt(const char* fmt, auto... args) {
  char buf[512];
  std::snprintf(buf, sizeof buf, fmt, args...);
  return buf;
}

}  // namespace

std::string LayoutAtlas(const formats::ReplayOutput& run, const AtlasGraph& graph,
                        const AtlasDrawOptions& options,
                        const std::vector<std::optional<Pose2>>* refined_frames,
                        AtlasLayout* layout, int* height_px, ViewTransform* view) {
  const int n = graph.FrameCount();
  if (!graph.HasFrame(options.source))
    return Fmt("source frame %d is not a frame of this atlas (frames 0..%d)", options.source,
               n - 1);
  *layout = AtlasLayout{};
  layout->frame_pose.assign(static_cast<size_t>(n), std::nullopt);
  layout->tree_parent_edge.assign(static_cast<size_t>(n), -1);
  const Projection projection = DijkstraProjection(graph, options.source);
  for (const ProjectedFrame& f : projection.entries) {
    layout->tree_parent_edge[static_cast<size_t>(f.frame)] = f.parent_edge;
    if (refined_frames == nullptr) layout->frame_pose[static_cast<size_t>(f.frame)] = f.pose;
  }
  if (refined_frames != nullptr) {
    // Refined poses are in frame 0's coordinates; re-express them in the source frame.
    const auto& src = (*refined_frames)[static_cast<size_t>(options.source)];
    if (!src) return Fmt("source frame %d has no refined pose", options.source);
    for (int f = 0; f < n && f < static_cast<int>(refined_frames->size()); ++f) {
      if (!(*refined_frames)[static_cast<size_t>(f)]) continue;
      UncertainPose p;
      p.mean = Between(*src, *(*refined_frames)[static_cast<size_t>(f)]);
      layout->frame_pose[static_cast<size_t>(f)] = p;
    }
  }
  std::vector<std::vector<const MapLine*>> lines(static_cast<size_t>(n));
  for (const formats::FrameLine& l : run.lines)
    if (l.frame >= 0 && l.frame < n) lines[static_cast<size_t>(l.frame)].push_back(&l.line);
  Box box;
  for (int f = 0; f < n; ++f) {
    const auto& p = layout->frame_pose[static_cast<size_t>(f)];
    if (!p) continue;
    ++layout->reached;
    box.Extend(Vec2(p->mean.x, p->mean.y));
    for (const MapLine* l : lines[static_cast<size_t>(f)]) {
      box.Extend(p->mean.TransformPoint(l->endpoint_a));
      box.Extend(p->mean.TransformPoint(l->endpoint_b));
    }
  }
  for (const Vec2& p : PlacedPoints(run.points, layout->frame_pose)) box.Extend(p);
  if (options.trajectory && options.source == 0) {
    for (const eval::TimedPose& s : options.refined ? run.refined : run.global)
      box.Extend(Vec2(s.pose.x, s.pose.y));
  }
  if (box.empty()) box.Extend(Vec2::Zero());
  box.min -= Vec2(1.0, 1.0);
  box.max += Vec2(1.0, 1.0);
  layout->min = box.min;
  layout->max = box.max;
  const Vec2 size = box.max - box.min;
  const double map_w = options.width_px - 2 * kMarginPx;
  const double scale = map_w / size.x();
  const double map_h = std::clamp(scale * size.y(), 200.0, 4.0 * options.width_px);
  *height_px = static_cast<int>(std::ceil(kHeaderPx + map_h + 2 * kMarginPx));
  *view = ViewTransform::Fit(box.min, box.max, kMarginPx, kHeaderPx + kMarginPx, map_w, map_h);
  return "";
}

void DrawAtlasProjection(Canvas& canvas, const formats::ReplayOutput& run, const AtlasGraph& graph,
                         const AtlasLayout& layout, const AtlasDrawOptions& options) {
  const int n = graph.FrameCount();
  const double px_per_m = canvas.view().pixels_per_metre();
  const auto pose_of = [&](FrameId f) -> const std::optional<UncertainPose>& {
    return layout.frame_pose[static_cast<size_t>(f)];
  };
  // The run's trajectory (global.tsv is in frame 0's coordinates).
  if (options.trajectory) {
    const auto& rows = options.refined ? run.refined : run.global;
    std::vector<Vec2> line;
    const auto& src = pose_of(0);
    const Pose2 to_source = src ? src->mean : Pose2{};
    if (src || options.source == 0) {
      line.reserve(rows.size());
      for (const eval::TimedPose& s : rows) {
        const Pose2 p = Compose(to_source, s.pose);
        line.emplace_back(p.x, p.y);
      }
      canvas.Polyline(line, Stroke{kTrajectoryColor, 1.0});
    }
  }
  // Edges: tree edges solid, map-match edges red dashed, others grey dashed.
  std::vector<std::pair<Vec2, Vec2>> tree, match, other;
  for (int i = 0; i < graph.EdgeCount(); ++i) {
    const AtlasEdge& e = graph.Edge(i);
    const auto& pa = pose_of(e.a);
    const auto& pb = pose_of(e.b);
    if (!pa || !pb) continue;
    const std::pair<Vec2, Vec2> seg{Vec2(pa->mean.x, pa->mean.y), Vec2(pb->mean.x, pb->mean.y)};
    const bool in_tree = layout.tree_parent_edge[static_cast<size_t>(e.a)] == i ||
                         layout.tree_parent_edge[static_cast<size_t>(e.b)] == i;
    if (in_tree) {
      tree.push_back(seg);
    } else if (e.kind == EdgeKind::kMapMatch || e.origin == EdgeKind::kMapMatch) {
      match.push_back(seg);
    } else {
      other.push_back(seg);
    }
  }
  canvas.Segments(tree, Stroke{kTreeColor, 1.5});
  canvas.Segments(match, Stroke{kMatchColor, 1.2, true});
  canvas.Segments(other, Stroke{kOtherEdgeColor, 1.0, true});
  // The points of every placed frame (points.tsv): the laser points it keeps for map-matching,
  // under its lines; without lines (grid frames: their occupied cells) they are the map.
  const bool points_are_map = run.lines.empty();
  const std::vector<Vec2> points = PlacedPoints(run.points, layout.frame_pose);
  canvas.Points(points, points_are_map ? kLineColor.WithAlpha(0.6) : kPointColor,
                std::clamp(0.05 * px_per_m, 0.6, 1.5));
  // Lines of every placed frame.
  std::vector<std::pair<Vec2, Vec2>> segments;
  segments.reserve(run.lines.size());
  for (const formats::FrameLine& l : run.lines) {
    if (l.frame < 0 || l.frame >= n || !pose_of(l.frame)) continue;
    const Pose2& p = pose_of(l.frame)->mean;
    segments.emplace_back(p.TransformPoint(l.line.endpoint_a), p.TransformPoint(l.line.endpoint_b));
  }
  canvas.Segments(segments, Stroke{kLineColor, std::clamp(0.05 * px_per_m, 1.0, 2.5)});
  // Frame origins, ellipses and labels.
  const double marker_m = 4.0 / px_per_m;
  for (int f = 0; f < n; ++f) {
    const auto& p = pose_of(f);
    if (!p) continue;
    const Vec2 c(p->mean.x, p->mean.y);
    if (options.ellipses && !options.refined && f != options.source)
      canvas.CovarianceEllipse(c, p->cov.topLeftCorner<2, 2>(), options.n_sigma,
                               Stroke{kEllipseColor, 1.0});
    canvas.Pose(p->mean, f == options.source ? 2 * marker_m : marker_m,
                f == options.source ? kSourceColor : kTreeColor.WithAlpha(1.0));
    if (options.frame_labels)
      canvas.TextAt(c + Vec2(marker_m, marker_m), std::to_string(f), 11, Color{0.2, 0.2, 0.2});
  }

  canvas.FillRectPx(0, 0, canvas.width_px(), kHeaderPx, Color{0.96, 0.96, 0.96});
  std::string title = options.title;
  if (title.empty()) {
    int match_edges = 0;
    for (const AtlasEdge& e : graph.Edges()) match_edges += e.origin == EdgeKind::kMapMatch;
    const std::string content = points_are_map ? Fmt("%zu occupied cells", run.points.size())
                                               : Fmt("%zu lines", run.lines.size());
    title =
        options.refined
            ? Fmt("atlas, global least-squares arrangement: %d frames, %d edges (%d by "
                  "map-matching), %s",
                  n, graph.EdgeCount(), match_edges, content.c_str())
            : Fmt("atlas, Dijkstra projection from frame %d: %d/%d frames, %d edges, %s%s",
                  options.source, layout.reached, n, graph.EdgeCount(), content.c_str(),
                  options.ellipses ? Fmt(", %.0f-sigma ellipses", options.n_sigma).c_str() : "");
  }
  canvas.TextPx(Vec2(kMarginPx, 22), title, 16, Color{0, 0, 0}, true);
  std::vector<LegendEntry> legend{
      points_are_map ? LegendEntry{"map: the frames' occupied cells", kLineColor, true}
                     : LegendEntry{"map lines", kLineColor},
      {"projection tree edges", kTreeColor},
      {"map-match edges off the tree", kMatchColor},
      {"other edges", kOtherEdgeColor},
      {"source frame", kSourceColor, true}};
  if (options.ellipses && !options.refined) legend.push_back({"frame uncertainty", kEllipseColor});
  if (!points.empty() && !points_are_map)
    legend.push_back({"laser points the frames keep (map-matching)", kPointColor, true});
  // Only when there is one to draw (an exported store has no trajectory: atlasd publishes the
  // poses, it does not save them).
  if (options.trajectory && !(options.refined ? run.refined : run.global).empty())
    legend.push_back({"robot trajectory", kTrajectoryColor});
  canvas.Legend(Vec2(kMarginPx, 46), legend);
  canvas.ScaleBar();
}

namespace {

// A plot rectangle in image pixels mapping data (x, y) to world coordinates of a canvas whose
// view is the identity on pixels with y up (see DrawTimeline).
struct Panel {
  double left, top, width, height;  // image px
  double x0, x1, y0, y1;            // data range
  double canvas_h;
  Vec2 At(double x, double y) const {
    const double px = left + (x - x0) / (x1 - x0) * width;
    const double py = top + height - (std::clamp(y, y0, y1) - y0) / (y1 - y0) * height;
    return Vec2(px, canvas_h - py);
  }
};

double NiceStep(double range, int ticks) {
  const double raw = range / std::max(ticks, 1);
  const double p = std::pow(10.0, std::floor(std::log10(raw)));
  for (double m : {1.0, 2.0, 5.0, 10.0})
    if (m * p >= raw) return m * p;
  return 10 * p;
}

void Axes(Canvas& canvas, const Panel& p, const std::string& xlabel, const std::string& ylabel) {
  const Color grid{0.85, 0.85, 0.85};
  const Color ink{0.1, 0.1, 0.1};
  const double xs = NiceStep(p.x1 - p.x0, 10), ys = NiceStep(p.y1 - p.y0, 6);
  for (double x = std::ceil(p.x0 / xs) * xs; x <= p.x1 + 1e-9; x += xs) {
    canvas.Line(p.At(x, p.y0), p.At(x, p.y1), Stroke{grid, 1.0});
    const Vec2 img(p.left + (x - p.x0) / (p.x1 - p.x0) * p.width - 10, p.top + p.height + 16);
    canvas.TextPx(img, Fmt("%g", x), 12, ink);
  }
  for (double y = std::ceil(p.y0 / ys) * ys; y <= p.y1 + 1e-9; y += ys) {
    canvas.Line(p.At(p.x0, y), p.At(p.x1, y), Stroke{grid, 1.0});
    const Vec2 img(p.left - 52, p.top + p.height - (y - p.y0) / (p.y1 - p.y0) * p.height + 4);
    canvas.TextPx(img, Fmt("%g", y), 12, ink);
  }
  canvas.Line(p.At(p.x0, p.y0), p.At(p.x1, p.y0), Stroke{ink, 1.2});
  canvas.Line(p.At(p.x0, p.y0), p.At(p.x0, p.y1), Stroke{ink, 1.2});
  canvas.TextPx(Vec2(p.left + p.width / 2 - 60, p.top + p.height + 34), xlabel, 13, ink);
  canvas.TextPx(Vec2(p.left, p.top - 8), ylabel, 13, ink, true);
}

}  // namespace

void DrawTimeline(Canvas& canvas, const std::vector<formats::TimingRecord>& timing,
                  const TimelineOptions& options) {
  const double W = canvas.width_px(), H = canvas.height_px();
  canvas.FillRectPx(0, 0, W, H, Color{1, 1, 1});
  canvas.TextPx(Vec2(kMarginPx, 24), options.title, 16, Color{0, 0, 0}, true);
  if (timing.empty()) return;
  const bool by_time = options.axis == TimelineAxis::kTime;
  std::vector<double> xs, ms;
  xs.reserve(timing.size());
  ms.reserve(timing.size());
  for (const formats::TimingRecord& r : timing) {
    xs.push_back(by_time ? (r.stamp_s - timing.front().stamp_s) / 60.0 : r.frames);
    ms.push_back(static_cast<double>(r.step_ns) * 1e-6);
  }
  std::vector<double> sorted = ms;
  std::sort(sorted.begin(), sorted.end());
  const double p999 = sorted[std::min(sorted.size() - 1, sorted.size() * 999 / 1000)];
  // Up to the budget (or a little beyond the largest step when all fit), so that the budget line
  // shows; steps beyond the top are drawn at the top edge.
  const double y_max = sorted.back() <= options.budget_ms * 1.2
                           ? std::max(sorted.back(), options.budget_ms) * 1.05
                           : std::max(p999 * 1.3, options.budget_ms * 1.15);
  const double x_min = *std::min_element(xs.begin(), xs.end());
  const double x_max = std::max(*std::max_element(xs.begin(), xs.end()), x_min + 1e-6);
  const double left = 80, right = 30;
  const double top1 = 70;
  const double h1 = by_time ? (H - top1 - 60) * 0.55 : H - top1 - 60;
  const Panel p1{left, top1, W - left - right, h1, x_min, x_max, 0.0, y_max, H};
  Axes(canvas, p1, by_time ? "time (min)" : "frames in the atlas",
       Fmt("%s; %zu steps, median %.3f ms, max %.3f ms%s", options.step_label.c_str(), ms.size(),
           sorted[sorted.size() / 2], sorted.back(), sorted.back() > y_max ? " (clipped)" : ""));
  std::vector<Vec2> pts;
  pts.reserve(ms.size());
  for (size_t i = 0; i < ms.size(); ++i) pts.push_back(p1.At(xs[i], ms[i]));
  canvas.Points(pts, Color{0.15, 0.35, 0.85, 0.5}, 1.2);
  // Running median over windows of 1 % of the steps (at least 25).
  const size_t win = std::max<size_t>(25, ms.size() / 100);
  std::vector<Vec2> med;
  std::vector<double> buf;
  for (size_t start = 0; start + win <= ms.size(); start += win / 2) {
    buf.assign(ms.begin() + static_cast<long>(start), ms.begin() + static_cast<long>(start + win));
    std::nth_element(buf.begin(), buf.begin() + static_cast<long>(win / 2), buf.end());
    med.push_back(p1.At(xs[start + win / 2], buf[win / 2]));
  }
  canvas.Polyline(med, Stroke{Color{0.85, 0.1, 0.1}, 2.0});
  if (options.budget_ms <= y_max)
    canvas.Line(p1.At(x_min, options.budget_ms), p1.At(x_max, options.budget_ms),
                Stroke{Color{0.1, 0.6, 0.2}, 1.5, true});
  canvas.Legend(Vec2(W - 560, top1 - 8),
                {{"step", Color{0.15, 0.35, 0.85}, true},
                 {"running median", Color{0.85, 0.1, 0.1}},
                 {Fmt("budget %.0f ms", options.budget_ms), Color{0.1, 0.6, 0.2}}});
  if (!by_time) return;
  int max_id = 1;
  for (const formats::TimingRecord& r : timing) max_id = std::max({max_id, r.dominant, r.frames});
  const double top2 = top1 + h1 + 70;
  const Panel p2{left,
                 top2,
                 W - left - right,
                 H - top2 - 50,
                 x_min,
                 x_max,
                 0.0,
                 static_cast<double>(max_id) * 1.05,
                 H};
  Axes(canvas, p2, "time (min)", "dominant map-frame id (and frame count, grey)");
  std::vector<Vec2> dom, count;
  for (size_t i = 0; i < timing.size(); ++i) {
    count.push_back(p2.At(xs[i], timing[i].frames));
    if (timing[i].dominant >= 0) dom.push_back(p2.At(xs[i], timing[i].dominant));
  }
  canvas.Polyline(count, Stroke{Color{0.6, 0.6, 0.6}, 1.2});
  canvas.Points(dom, Color{0.1, 0.1, 0.1}, 1.0);
}

}  // namespace atlas::draw
