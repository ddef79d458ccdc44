#include "tools/render/canvas.h"

#include <cairo-svg.h>
#include <fontconfig/fontconfig.h>

#include <Eigen/Eigenvalues>
#include <algorithm>
#include <cmath>
#include <numbers>

namespace atlas::draw {

void ReleaseDrawingCaches() {
  cairo_debug_reset_static_data();
  FcFini();
}

ViewTransform ViewTransform::Fit(const Vec2& world_min, const Vec2& world_max, double left_px,
                                 double top_px, double width_px, double height_px) {
  ViewTransform v;
  const Vec2 size = (world_max - world_min).cwiseMax(Vec2(1e-6, 1e-6));
  v.scale_ = std::min(width_px / size.x(), height_px / size.y());
  // Centre: the world box's top-left corner goes to the offset.
  const double used_w = v.scale_ * size.x(), used_h = v.scale_ * size.y();
  v.world_origin_ = Vec2(world_min.x(), world_max.y());
  v.image_offset_ = Vec2(left_px + 0.5 * (width_px - used_w), top_px + 0.5 * (height_px - used_h));
  return v;
}

Vec2 ViewTransform::ToImage(const Vec2& w) const {
  return Vec2(image_offset_.x() + scale_ * (w.x() - world_origin_.x()),
              image_offset_.y() - scale_ * (w.y() - world_origin_.y()));
}

Vec2 ViewTransform::ToWorld(const Vec2& p) const {
  return Vec2(world_origin_.x() + (p.x() - image_offset_.x()) / scale_,
              world_origin_.y() - (p.y() - image_offset_.y()) / scale_);
}

bool ImageFormatOf(const std::string& path, ImageFormat* format) {
  auto ends_with = [&](const char* ext) {
    const std::string e(ext);
    if (path.size() < e.size()) return false;
    std::string tail = path.substr(path.size() - e.size());
    std::transform(tail.begin(), tail.end(), tail.begin(), ::tolower);
    return tail == e;
  };
  if (ends_with(".png")) {
    *format = ImageFormat::kPng;
    return true;
  }
  if (ends_with(".svg")) {
    *format = ImageFormat::kSvg;
    return true;
  }
  return false;
}

std::unique_ptr<Canvas> Canvas::Create(ImageFormat format, const std::string& path, int width_px,
                                       int height_px, const ViewTransform& view,
                                       std::string* error) {
  if (width_px < 16 || height_px < 16 || width_px > 20000 || height_px > 20000) {
    *error = "image size must be between 16 and 20000 pixels a side";
    return nullptr;
  }
  cairo_surface_t* surface =
      format == ImageFormat::kPng
          ? cairo_image_surface_create(CAIRO_FORMAT_ARGB32, width_px, height_px)
          : cairo_svg_surface_create(path.c_str(), width_px, height_px);
  if (cairo_surface_status(surface) != CAIRO_STATUS_SUCCESS) {
    *error = "cannot create " + path + ": " + cairo_status_to_string(cairo_surface_status(surface));
    cairo_surface_destroy(surface);
    return nullptr;
  }
  std::unique_ptr<Canvas> c(new Canvas(format, path, width_px, height_px, view, surface));
  c->FillRectPx(0, 0, width_px, height_px, Color{1, 1, 1});
  return c;
}

Canvas::Canvas(ImageFormat format, std::string path, int width, int height,
               const ViewTransform& view, cairo_surface_t* surface)
    : format_(format),
      path_(std::move(path)),
      width_(width),
      height_(height),
      view_(view),
      surface_(surface),
      cr_(cairo_create(surface)) {
  cairo_set_line_join(cr_, CAIRO_LINE_JOIN_ROUND);
  cairo_set_line_cap(cr_, CAIRO_LINE_CAP_ROUND);
}

Canvas::~Canvas() {
  Finish();
  if (cr_) cairo_destroy(cr_);
  if (surface_) cairo_surface_destroy(surface_);
}

std::string Canvas::Finish() {
  if (finished_) return "";
  finished_ = true;
  std::string error;
  if (cairo_status(cr_) != CAIRO_STATUS_SUCCESS)
    error = std::string("drawing failed: ") + cairo_status_to_string(cairo_status(cr_));
  if (format_ == ImageFormat::kPng) {
    const cairo_status_t s = cairo_surface_write_to_png(surface_, path_.c_str());
    if (s != CAIRO_STATUS_SUCCESS && error.empty())
      error = "cannot write " + path_ + ": " + cairo_status_to_string(s);
  } else {
    cairo_surface_finish(surface_);
    if (cairo_surface_status(surface_) != CAIRO_STATUS_SUCCESS && error.empty())
      error =
          "cannot write " + path_ + ": " + cairo_status_to_string(cairo_surface_status(surface_));
  }
  return error;
}

void Canvas::SetColor(const Color& c) { cairo_set_source_rgba(cr_, c.r, c.g, c.b, c.a); }

void Canvas::SetStroke(const Stroke& s) {
  SetColor(s.color);
  cairo_set_line_width(cr_, s.width_px);
  if (s.dashed) {
    const double dash[] = {4.0 * s.width_px, 3.0 * s.width_px};
    cairo_set_dash(cr_, dash, 2, 0.0);
  } else {
    cairo_set_dash(cr_, nullptr, 0, 0.0);
  }
}

void Canvas::Line(const Vec2& a, const Vec2& b, const Stroke& stroke) {
  Segments({{a, b}}, stroke);
}

void Canvas::Segments(const std::vector<std::pair<Vec2, Vec2>>& segments, const Stroke& stroke) {
  if (finished_ || segments.empty()) return;
  SetStroke(stroke);
  for (const auto& [a, b] : segments) {
    const Vec2 p = view_.ToImage(a), q = view_.ToImage(b);
    cairo_move_to(cr_, p.x(), p.y());
    cairo_line_to(cr_, q.x(), q.y());
  }
  cairo_stroke(cr_);
}

void Canvas::Polyline(const std::vector<Vec2>& points, const Stroke& stroke) {
  if (finished_ || points.size() < 2) return;
  SetStroke(stroke);
  Vec2 last = view_.ToImage(points[0]);
  cairo_move_to(cr_, last.x(), last.y());
  for (size_t i = 1; i < points.size(); ++i) {
    const Vec2 p = view_.ToImage(points[i]);
    // Skip sub-pixel steps: long trajectories stay light in SVG.
    if ((p - last).squaredNorm() < 0.25 && i + 1 < points.size()) continue;
    cairo_line_to(cr_, p.x(), p.y());
    last = p;
  }
  cairo_stroke(cr_);
}

void Canvas::Points(const std::vector<Vec2>& points, const Color& color, double radius_px) {
  if (finished_ || points.empty()) return;
  SetColor(color);
  const double r = radius_px;
  for (const Vec2& w : points) {
    const Vec2 p = view_.ToImage(w);
    if (p.x() < -r || p.y() < -r || p.x() > width_ + r || p.y() > height_ + r) continue;
    cairo_rectangle(cr_, p.x() - r, p.y() - r, 2 * r, 2 * r);
  }
  cairo_fill(cr_);
}

void Canvas::Circle(const Vec2& centre, double radius_m, const Stroke& stroke) {
  if (finished_) return;
  SetStroke(stroke);
  const Vec2 p = view_.ToImage(centre);
  cairo_new_sub_path(cr_);
  cairo_arc(cr_, p.x(), p.y(), radius_m * view_.pixels_per_metre(), 0, 2 * std::numbers::pi);
  cairo_stroke(cr_);
}

void Canvas::FilledCircle(const Vec2& centre, double radius_px, const Color& color) {
  if (finished_) return;
  SetColor(color);
  const Vec2 p = view_.ToImage(centre);
  cairo_new_sub_path(cr_);
  cairo_arc(cr_, p.x(), p.y(), radius_px, 0, 2 * std::numbers::pi);
  cairo_fill(cr_);
}

void Canvas::CovarianceEllipse(const Vec2& centre, const Eigen::Matrix2d& cov, double n_sigma,
                               const Stroke& stroke) {
  if (finished_) return;
  const Eigen::SelfAdjointEigenSolver<Eigen::Matrix2d> eig(0.5 * (cov + cov.transpose()));
  if (eig.info() != Eigen::Success) return;
  const Eigen::Vector2d axes = eig.eigenvalues().cwiseMax(0.0).cwiseSqrt() * n_sigma;
  const Eigen::Matrix2d v = eig.eigenvectors();
  std::vector<Vec2> pts;
  for (int i = 0; i <= 72; ++i) {
    const double a = 2.0 * std::numbers::pi * i / 72;
    pts.push_back(centre + v * Eigen::Vector2d(axes.x() * std::cos(a), axes.y() * std::sin(a)));
  }
  SetStroke(stroke);
  for (size_t i = 0; i < pts.size(); ++i) {
    const Vec2 p = view_.ToImage(pts[i]);
    i == 0 ? cairo_move_to(cr_, p.x(), p.y()) : cairo_line_to(cr_, p.x(), p.y());
  }
  cairo_close_path(cr_);
  cairo_stroke(cr_);
}

void Canvas::Arrow(const Vec2& from, const Vec2& to, const Stroke& stroke, double head_px) {
  if (finished_) return;
  const Vec2 p = view_.ToImage(from), q = view_.ToImage(to);
  SetStroke(stroke);
  cairo_move_to(cr_, p.x(), p.y());
  cairo_line_to(cr_, q.x(), q.y());
  cairo_stroke(cr_);
  const Vec2 d = q - p;
  if (d.norm() < 1e-9) return;
  const Vec2 u = d.normalized(), n(-u.y(), u.x());
  const Vec2 a = q - head_px * u + 0.5 * head_px * n, b = q - head_px * u - 0.5 * head_px * n;
  SetColor(stroke.color);
  cairo_move_to(cr_, q.x(), q.y());
  cairo_line_to(cr_, a.x(), a.y());
  cairo_line_to(cr_, b.x(), b.y());
  cairo_close_path(cr_);
  cairo_fill(cr_);
}

void Canvas::Pose(const Pose2& pose, double radius_m, const Color& color) {
  if (finished_) return;
  const Vec2 c(pose.x, pose.y);
  const double r_px = std::max(3.0, radius_m * view_.pixels_per_metre());
  FilledCircle(c, r_px, color);
  const Vec2 tip = c + (2.2 * r_px / view_.pixels_per_metre()) *
                           Vec2(std::cos(pose.theta), std::sin(pose.theta));
  Arrow(c, tip, Stroke{color, 2.0}, 6.0);
}

void Canvas::TextPx(const Vec2& at_px, const std::string& text, double size_px, const Color& color,
                    bool bold) {
  if (finished_) return;
  SetColor(color);
  cairo_select_font_face(cr_, "sans-serif", CAIRO_FONT_SLANT_NORMAL,
                         bold ? CAIRO_FONT_WEIGHT_BOLD : CAIRO_FONT_WEIGHT_NORMAL);
  cairo_set_font_size(cr_, size_px);
  cairo_move_to(cr_, at_px.x(), at_px.y());
  cairo_show_text(cr_, text.c_str());
}

void Canvas::TextAt(const Vec2& world, const std::string& text, double size_px,
                    const Color& color) {
  TextPx(view_.ToImage(world), text, size_px, color);
}

void Canvas::FillRectPx(double x, double y, double w, double h, const Color& color) {
  if (finished_) return;
  SetColor(color);
  cairo_rectangle(cr_, x, y, w, h);
  cairo_fill(cr_);
}

void Canvas::ScaleBar() {
  if (finished_) return;
  // The largest round length not longer than a fifth of the image width.
  const double max_m = 0.2 * width_ / view_.pixels_per_metre();
  double len = std::pow(10.0, std::floor(std::log10(max_m)));
  for (double f : {5.0, 2.0})
    if (len * f <= max_m) {
      len *= f;
      break;
    }
  const double px = len * view_.pixels_per_metre();
  const double x = 20, y = height_ - 20;
  FillRectPx(x - 6, y - 24, px + 70, 34, Color{1, 1, 1, 0.85});
  SetStroke(Stroke{Color{0, 0, 0}, 3.0});
  cairo_move_to(cr_, x, y);
  cairo_line_to(cr_, x + px, y);
  cairo_move_to(cr_, x, y - 6);
  cairo_line_to(cr_, x, y + 4);
  cairo_move_to(cr_, x + px, y - 6);
  cairo_line_to(cr_, x + px, y + 4);
  cairo_stroke(cr_);
  char label[32];
  std::snprintf(label, sizeof(label), len >= 1.0 ? "%.0f m" : "%.2g m", len);
  TextPx(Vec2(x + px + 8, y + 4), label, 14, Color{0, 0, 0});
}

void Canvas::Legend(const Vec2& at_px, const std::vector<LegendEntry>& entries) {
  if (finished_) return;
  double x = at_px.x();
  const double y = at_px.y();
  cairo_set_font_size(cr_, 14);
  for (const LegendEntry& e : entries) {
    if (e.points) {
      cairo_new_sub_path(cr_);
      SetColor(e.color.WithAlpha(1.0));
      cairo_arc(cr_, x + 12, y - 5, 4, 0, 2 * std::numbers::pi);
      cairo_fill(cr_);
    } else {
      SetStroke(Stroke{e.color.WithAlpha(1.0), 3.0});
      cairo_move_to(cr_, x, y - 5);
      cairo_line_to(cr_, x + 24, y - 5);
      cairo_stroke(cr_);
    }
    TextPx(Vec2(x + 30, y), e.label, 14, Color{0.1, 0.1, 0.1});
    cairo_text_extents_t ext;
    cairo_text_extents(cr_, e.label.c_str(), &ext);
    x += 30 + ext.x_advance + 24;
  }
}

}  // namespace atlas::draw
