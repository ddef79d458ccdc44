#pragma once
// A drawing surface for maps: PNG or SVG through cairo, with world coordinates in metres
// (x right, y up) mapped onto the image by a ViewTransform fitted to the content.
//
// Primitives take world coordinates unless named *Px (image pixels, y down). Line widths and
// point sizes are in pixels so that a picture reads the same at any scale. Used by atlas-render
// for simulated runs, and meant for drawing the atlas (map-frames, their edges and covariance
// ellipses) later.

#include <cairo.h>

#include <memory>
#include <string>
#include <vector>

#include "core/geometry/se2.h"

namespace atlas::draw {

struct Color {
  double r = 0.0, g = 0.0, b = 0.0, a = 1.0;
  Color WithAlpha(double alpha) const { return Color{r, g, b, alpha}; }
};

struct Stroke {
  Color color;
  double width_px = 1.0;
  bool dashed = false;
};

// World (m, y up) to image (px, y down): image = scale * (world - world_min) with y flipped,
// offset into the map area.
class ViewTransform {
 public:
  ViewTransform() = default;
  // Fits the world box [min, max] into the image rectangle (left, top, width, height) px,
  // keeping the aspect ratio, centred.
  static ViewTransform Fit(const Vec2& world_min, const Vec2& world_max, double left_px,
                           double top_px, double width_px, double height_px);
  Vec2 ToImage(const Vec2& world) const;
  Vec2 ToWorld(const Vec2& image) const;
  double pixels_per_metre() const { return scale_; }

 private:
  double scale_ = 1.0;
  Vec2 world_origin_ = Vec2::Zero();  // world point at image (offset_x, offset_y)
  Vec2 image_offset_ = Vec2::Zero();
};

enum class ImageFormat { kPng, kSvg };
// The format named by a path's extension (.png or .svg); false if neither.
bool ImageFormatOf(const std::string& path, ImageFormat* format);

struct LegendEntry {
  std::string label;
  Color color;
  bool points = false;  // drawn as a dot instead of a line
};

// Frees cairo's and fontconfig's process-wide caches (font lists, glyphs). Call once when no
// canvas exists any more and none will be made (end of a tool, test teardown), so that leak
// checkers see a clean exit.
void ReleaseDrawingCaches();

class Canvas {
 public:
  // A white canvas of width x height px that Finish() writes to `path`. On failure returns
  // nullptr and sets *error.
  static std::unique_ptr<Canvas> Create(ImageFormat format, const std::string& path, int width_px,
                                        int height_px, const ViewTransform& view,
                                        std::string* error);
  ~Canvas();
  Canvas(const Canvas&) = delete;
  Canvas& operator=(const Canvas&) = delete;

  // Writes the file. Returns "" or what went wrong. Drawing after Finish() is ignored.
  std::string Finish();

  const ViewTransform& view() const { return view_; }
  int width_px() const { return width_; }
  int height_px() const { return height_; }

  void Line(const Vec2& a, const Vec2& b, const Stroke& stroke);
  // Many unconnected segments (a[i], b[i]) in one stroke.
  void Segments(const std::vector<std::pair<Vec2, Vec2>>& segments, const Stroke& stroke);
  void Polyline(const std::vector<Vec2>& points, const Stroke& stroke);
  // Filled squares of side 2 * radius_px centred on each point.
  void Points(const std::vector<Vec2>& points, const Color& color, double radius_px);
  void Circle(const Vec2& centre, double radius_m, const Stroke& stroke);
  void FilledCircle(const Vec2& centre, double radius_px, const Color& color);
  // The n-sigma ellipse of a 2x2 position covariance (m^2) centred at `centre`.
  void CovarianceEllipse(const Vec2& centre, const Eigen::Matrix2d& cov, double n_sigma,
                         const Stroke& stroke);
  // An arrow from `from` to `to` with a head of head_px pixels.
  void Arrow(const Vec2& from, const Vec2& to, const Stroke& stroke, double head_px = 8.0);
  // A robot pose: a filled circle with a heading tick, radius in metres.
  void Pose(const Pose2& pose, double radius_m, const Color& color);
  // Text with its baseline-left corner at `at_px` (image pixels).
  void TextPx(const Vec2& at_px, const std::string& text, double size_px, const Color& color,
              bool bold = false);
  void TextAt(const Vec2& world, const std::string& text, double size_px, const Color& color);
  void FillRectPx(double x, double y, double w, double h, const Color& color);
  // A bar of a round length (1, 2, 5 x 10^k m) near the bottom-left corner.
  void ScaleBar();
  // A row of legend entries starting at `at_px`.
  void Legend(const Vec2& at_px, const std::vector<LegendEntry>& entries);

 private:
  Canvas(ImageFormat format, std::string path, int width, int height, const ViewTransform& view,
         cairo_surface_t* surface);
  void SetStroke(const Stroke& stroke);
  void SetColor(const Color& color);

  ImageFormat format_;
  std::string path_;
  int width_, height_;
  ViewTransform view_;
  cairo_surface_t* surface_ = nullptr;
  cairo_t* cr_ = nullptr;
  bool finished_ = false;
};

}  // namespace atlas::draw
