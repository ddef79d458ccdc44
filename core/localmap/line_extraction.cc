#include "core/localmap/line_extraction.h"

#include <algorithm>
#include <cmath>

namespace atlas {
namespace {

struct Segment {
  int begin;  // index into points, inclusive
  int end;    // exclusive
};

// Max normal distance to the chord through the first and last point; returns its index.
int FarthestFromChord(const std::vector<Vec2>& p, int begin, int end, double& dist) {
  const Vec2 a = p[begin], b = p[end - 1];
  Vec2 d = b - a;
  const double len = d.norm();
  int best = begin;
  dist = 0.0;
  for (int i = begin + 1; i < end - 1; ++i) {
    const double di = len > 1e-12
                          ? std::abs(d.x() * (p[i].y() - a.y()) - d.y() * (p[i].x() - a.x())) / len
                          : (p[i] - a).norm();
    if (di > dist) {
      dist = di;
      best = i;
    }
  }
  return best;
}

// Max normal distance of the points to their unweighted total-least-squares line.
double MaxResidualTls(const std::vector<Vec2>& p, int begin, int end) {
  const int n = end - begin;
  double cx = 0.0, cy = 0.0;
  for (int i = begin; i < end; ++i) {
    cx += p[i].x();
    cy += p[i].y();
  }
  cx /= n;
  cy /= n;
  double sxx = 0.0, syy = 0.0, sxy = 0.0;
  for (int i = begin; i < end; ++i) {
    const double dx = p[i].x() - cx, dy = p[i].y() - cy;
    sxx += dx * dx;
    syy += dy * dy;
    sxy += dx * dy;
  }
  const double alpha = 0.5 * std::atan2(-2.0 * sxy, syy - sxx);
  const double ca = std::cos(alpha), sa = std::sin(alpha);
  double worst = 0.0;
  for (int i = begin; i < end; ++i) {
    worst = std::max(worst, std::abs((p[i].x() - cx) * ca + (p[i].y() - cy) * sa));
  }
  return worst;
}

}  // namespace

bool FitLine(const std::vector<Vec2>& points, const std::vector<double>& range_var,
             double model_var, ObservedLine& line) {
  const int n = static_cast<int>(points.size());
  if (n < 2) return false;
  // Unweighted fit, then reweighted twice with the fitted angle: the normal variance of point i
  // is range_var_i (u_i . normal)^2 + model_var, u_i the unit bearing of the point.
  double alpha = 0.0, rho = 0.0;
  double w_buf[512];
  std::vector<double> w_heap;
  double* w = w_buf;
  if (n > 512) {
    w_heap.resize(n);
    w = w_heap.data();
  }
  for (int i = 0; i < n; ++i) w[i] = 1.0;
  for (int iter = 0; iter < 3; ++iter) {
    if (iter > 0) {
      const double ca = std::cos(alpha), sa = std::sin(alpha);
      for (int i = 0; i < n; ++i) {
        const double r2 = points[i].squaredNorm();
        const double c = points[i].x() * ca + points[i].y() * sa;  // r cos(phi - alpha)
        w[i] = 1.0 / std::max(r2 > 0.0 ? range_var[i] * c * c / r2 + model_var : model_var, 1e-12);
      }
    }
    double sw = 0.0, cx = 0.0, cy = 0.0;
    for (int i = 0; i < n; ++i) {
      sw += w[i];
      cx += w[i] * points[i].x();
      cy += w[i] * points[i].y();
    }
    cx /= sw;
    cy /= sw;
    double sxx = 0.0, syy = 0.0, sxy = 0.0;
    for (int i = 0; i < n; ++i) {
      const double dx = points[i].x() - cx, dy = points[i].y() - cy;
      sxx += w[i] * dx * dx;
      syy += w[i] * dy * dy;
      sxy += w[i] * dx * dy;
    }
    // Normal angle minimising sum w (n . (p - c))^2.
    alpha = 0.5 * std::atan2(-2.0 * sxy, syy - sxx);
    rho = cx * std::cos(alpha) + cy * std::sin(alpha);
    if (rho < 0.0) {
      rho = -rho;
      alpha += std::numbers::pi;
    }
    alpha = WrapAngle(alpha);
  }
  double i00 = 0.0, i01 = 0.0, i11 = 0.0;
  const double ca = std::cos(alpha), sa = std::sin(alpha);
  for (int i = 0; i < n; ++i) {
    const double j1 = -points[i].x() * sa + points[i].y() * ca;
    i00 += w[i];
    i01 -= w[i] * j1;
    i11 += w[i] * j1 * j1;
  }
  const double det = i00 * i11 - i01 * i01;
  if (!(det > 1e-300) || !std::isfinite(det)) return false;
  line.rho = rho;
  line.alpha = alpha;
  line.cov << i11 / det, -i01 / det, -i01 / det, i00 / det;
  const double ta = PositionAlongLine(alpha, points.front());
  const double tb = PositionAlongLine(alpha, points.back());
  line.endpoint_a = PointOnLine(rho, alpha, ta);
  line.endpoint_b = PointOnLine(rho, alpha, tb);
  line.num_points = n;
  return true;
}

std::vector<ObservedLine> ExtractLines(const LaserScan& scan,
                                       const LineExtractionOptions& options) {
  std::vector<ObservedLine> lines;
  const int beams = static_cast<int>(scan.ranges.size());
  if (beams == 0) return lines;
  std::vector<Vec2> pts;
  std::vector<double> var;
  std::vector<int> beam_of;
  pts.reserve(beams);
  var.reserve(beams);
  beam_of.reserve(beams);
  const double max_range = scan.max_range > 0.0f ? scan.max_range : 1e30;
  std::vector<Segment> clusters;
  int cluster_begin = 0;
  for (int i = 0; i < beams; ++i) {
    const float r = scan.ranges[i];
    if (!IsReturn(r) || r < options.min_range || r >= max_range) continue;
    const double phi = scan.angle_min + static_cast<double>(i) * scan.angle_increment;
    const Vec2 p(r * std::cos(phi), r * std::sin(phi));
    if (!pts.empty() && (p - pts.back()).norm() > options.max_gap) {
      clusters.push_back({cluster_begin, static_cast<int>(pts.size())});
      cluster_begin = static_cast<int>(pts.size());
    }
    const double sigma = options.range_sigma + options.range_sigma_per_m * r;
    pts.push_back(p);
    var.push_back(sigma * sigma);
    beam_of.push_back(i);
  }
  if (!pts.empty()) clusters.push_back({cluster_begin, static_cast<int>(pts.size())});

  std::vector<Segment> segments;
  std::vector<Segment> stack;
  for (const Segment& cl : clusters) {
    if (cl.end - cl.begin < options.min_points) continue;
    const size_t first_of_cluster = segments.size();
    stack.clear();
    stack.push_back(cl);
    while (!stack.empty()) {
      const Segment s = stack.back();
      stack.pop_back();
      if (s.end - s.begin < 3) {
        segments.push_back(s);
        continue;
      }
      double dist = 0.0;
      const int k = FarthestFromChord(pts, s.begin, s.end, dist);
      if (dist > options.split_distance) {
        // Later part pushed first so that segments come out in beam order.
        stack.push_back({k + 1, s.end});
        stack.push_back({s.begin, k + 1});
      } else {
        segments.push_back(s);
      }
    }
    // Merge adjacent collinear segments of this cluster.
    std::vector<Segment> merged;
    for (size_t i = first_of_cluster; i < segments.size(); ++i) {
      if (!merged.empty() &&
          MaxResidualTls(pts, merged.back().begin, segments[i].end) <= options.split_distance) {
        merged.back().end = segments[i].end;
      } else {
        merged.push_back(segments[i]);
      }
    }
    segments.resize(first_of_cluster);
    segments.insert(segments.end(), merged.begin(), merged.end());
  }

  std::vector<Vec2> seg_pts;
  std::vector<double> seg_var;
  const double model_var = options.model_sigma * options.model_sigma;
  for (const Segment& s : segments) {
    if (s.end - s.begin < options.min_points) continue;
    // Fit, then trim end points that do not belong to the line (the neighbour wall's points
    // near a corner, mixed pixels) and refit.
    int b = s.begin, e = s.end;
    ObservedLine line;
    bool ok = false;
    for (int round = 0; round < 4; ++round) {
      seg_pts.assign(pts.begin() + b, pts.begin() + e);
      seg_var.assign(var.begin() + b, var.begin() + e);
      ok = FitLine(seg_pts, seg_var, model_var, line);
      if (!ok) break;
      const double ca = std::cos(line.alpha), sa = std::sin(line.alpha);
      const auto outlier = [&](int i) {
        const double proj = pts[i].x() * ca + pts[i].y() * sa;
        const double d = proj - line.rho;
        const double c2 = proj * proj / std::max(pts[i].squaredNorm(), 1e-12);
        return d * d > 9.0 * (var[i] * c2 + model_var);
      };
      const int b0 = b, e0 = e;
      while (e - b > options.min_points && outlier(b)) ++b;
      while (e - b > options.min_points && outlier(e - 1)) --e;
      if (b == b0 && e == e0) break;
    }
    if (!ok || e - b < options.min_points || line.Length() < options.min_length) continue;
    line.cov(0, 0) += options.min_rho_sigma * options.min_rho_sigma;
    line.cov(1, 1) += options.min_alpha_sigma * options.min_alpha_sigma;
    line.first_beam = beam_of[b];
    line.last_beam = beam_of[e - 1];
    lines.push_back(line);
  }
  if (static_cast<int>(lines.size()) > options.max_lines) {
    std::stable_sort(lines.begin(), lines.end(), [](const ObservedLine& a, const ObservedLine& b) {
      return a.Length() > b.Length();
    });
    lines.resize(options.max_lines);
    std::stable_sort(lines.begin(), lines.end(), [](const ObservedLine& a, const ObservedLine& b) {
      return a.first_beam < b.first_beam;
    });
  }
  return lines;
}

std::vector<ObservedLine> ExtractRobotFrameLines(const LaserScan& scan,
                                                 const LineExtractionOptions& options) {
  std::vector<ObservedLine> lines = ExtractLines(scan, options);
  for (ObservedLine& l : lines) l = ObservedLineToParent(scan.sensor_pose, l);
  return lines;
}

}  // namespace atlas
