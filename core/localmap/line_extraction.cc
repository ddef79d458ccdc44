#include "core/localmap/line_extraction.h"

#include <Eigen/Eigenvalues>
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
  Vec2 c = Vec2::Zero();
  for (int i = begin; i < end; ++i) c += p[i];
  c /= n;
  Mat2 m = Mat2::Zero();
  for (int i = begin; i < end; ++i) m += (p[i] - c) * (p[i] - c).transpose();
  Eigen::SelfAdjointEigenSolver<Mat2> es(m);
  const Vec2 normal = es.eigenvectors().col(0);
  double worst = 0.0;
  for (int i = begin; i < end; ++i) worst = std::max(worst, std::abs(normal.dot(p[i] - c)));
  return worst;
}

}  // namespace

bool FitLine(const std::vector<Vec2>& points, const std::vector<double>& range_var,
             double model_var, ObservedLine& line) {
  const int n = static_cast<int>(points.size());
  if (n < 2) return false;
  // Start from the unweighted fit, then reweight twice with the fitted angle.
  double alpha = 0.0, rho = 0.0;
  std::vector<double> w(n, 1.0);
  for (int iter = 0; iter < 3; ++iter) {
    if (iter > 0) {
      for (int i = 0; i < n; ++i) {
        const double phi = std::atan2(points[i].y(), points[i].x());
        const double c = std::cos(phi - alpha);
        w[i] = 1.0 / std::max(range_var[i] * c * c + model_var, 1e-12);
      }
    }
    double sw = 0.0;
    Vec2 c = Vec2::Zero();
    for (int i = 0; i < n; ++i) {
      sw += w[i];
      c += w[i] * points[i];
    }
    c /= sw;
    Mat2 m = Mat2::Zero();
    for (int i = 0; i < n; ++i) m += w[i] * (points[i] - c) * (points[i] - c).transpose();
    const double sxx = m(0, 0), syy = m(1, 1), sxy = m(0, 1);
    // Normal angle minimising sum w (n . (p - c))^2.
    alpha = 0.5 * std::atan2(-2.0 * sxy, syy - sxx);
    rho = c.x() * std::cos(alpha) + c.y() * std::sin(alpha);
    if (rho < 0.0) {
      rho = -rho;
      alpha += std::numbers::pi;
    }
    alpha = WrapAngle(alpha);
  }
  Mat2 info = Mat2::Zero();
  const double ca = std::cos(alpha), sa = std::sin(alpha);
  for (int i = 0; i < n; ++i) {
    const Eigen::RowVector2d j(-1.0, -points[i].x() * sa + points[i].y() * ca);
    info += w[i] * j.transpose() * j;
  }
  const double det = info.determinant();
  if (!(det > 1e-300) || !std::isfinite(det)) return false;
  line.rho = rho;
  line.alpha = alpha;
  line.cov = info.inverse();
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
  for (const Segment& s : segments) {
    if (s.end - s.begin < options.min_points) continue;
    seg_pts.assign(pts.begin() + s.begin, pts.begin() + s.end);
    seg_var.assign(var.begin() + s.begin, var.begin() + s.end);
    ObservedLine line;
    if (!FitLine(seg_pts, seg_var, options.model_sigma * options.model_sigma, line)) continue;
    if (line.Length() < options.min_length) continue;
    line.first_beam = beam_of[s.begin];
    line.last_beam = beam_of[s.end - 1];
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
