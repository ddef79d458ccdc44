#include "core/localmap/line_extraction.h"

#include <algorithm>
#include <cmath>
#include <numbers>

#include "core/localmap/jcbb.h"

namespace atlas {
namespace {

// 4 sigma of the noise of the spacing of two points along a line, sqrt(2) sigma_r |sin|.
constexpr double kSpacingMargin = 4.0 * std::numbers::sqrt2;

struct Segment {
  int begin;  // index into points, inclusive
  int end;    // exclusive
};

struct Scratch {
  std::vector<Vec2> pts;
  std::vector<double> var;
  std::vector<double> range;  // of each point
  std::vector<int> beam_of;
  std::vector<Segment> clusters, segments, stack, merged;
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

// The fit of FitLine with each point's range given (|p_i|, the beam's range).
bool FitLineRanged(std::span<const Vec2> points, const double* ranges,
                   std::span<const double> range_var, double model_var, ObservedLine& line);

}  // namespace

bool FitLine(const std::vector<Vec2>& points, const std::vector<double>& range_var,
             double model_var, ObservedLine& line) {
  if (range_var.size() != points.size()) return false;
  return FitLine(std::span<const Vec2>(points), std::span<const double>(range_var), model_var,
                 line);
}

bool FitLine(std::span<const Vec2> points, std::span<const double> range_var, double model_var,
             ObservedLine& line) {
  if (range_var.size() != points.size()) return false;
  std::vector<double> ranges(points.size());
  for (size_t i = 0; i < points.size(); ++i) ranges[i] = points[i].norm();
  return FitLineRanged(points, ranges.data(), range_var, model_var, line);
}

namespace {

bool FitLineRanged(std::span<const Vec2> points, const double* ranges,
                   std::span<const double> range_var, double model_var, ObservedLine& line) {
  const int n = static_cast<int>(points.size());
  if (n < 2) return false;
  // Start: the unweighted total-least-squares line through the centroid.
  double cx = 0.0, cy = 0.0;
  for (int i = 0; i < n; ++i) {
    cx += points[i].x();
    cy += points[i].y();
  }
  cx /= n;
  cy /= n;
  double sxx = 0.0, syy = 0.0, sxy = 0.0;
  for (int i = 0; i < n; ++i) {
    const double dx = points[i].x() - cx, dy = points[i].y() - cy;
    sxx += dx * dx;
    syy += dy * dy;
    sxy += dx * dy;
  }
  // Normal angle minimising sum (n . (p - c))^2: 2 alpha = atan2(-2 sxy, syy - sxx); the normal
  // (ca, sa) = (cos alpha, sin alpha) from the double angle, without trigonometry.
  const double c2 = syy - sxx, s2 = -2.0 * sxy;
  const double h = std::sqrt(c2 * c2 + s2 * s2);
  if (!(h > 0.0) || !std::isfinite(h)) return false;
  double ca = std::sqrt(std::max(0.0, 0.5 * (1.0 + c2 / h)));
  double sa = std::copysign(std::sqrt(std::max(0.0, 0.5 * (1.0 - c2 / h))), s2);
  double rho = cx * ca + cy * sa;
  if (rho < 0.0) {
    rho = -rho;
    ca = -ca;
    sa = -sa;
  }
  // A total-least-squares fit (weighted or not) is biased when the noise is along the beams:
  // its normal equations use the noisy along-line coordinate of each point, which correlates
  // with the point's normal residual (errors in variables; at grazing incidence the bias
  // reaches a tenth of a sigma per fit, and a feature seen in thousands of scans accumulates
  // it). A Gauss-Newton step on the ranges themselves, r_i = rho / cos(phi_i - alpha) with
  // exact bearings and variance range_var_i + model_var / cos^2, has an unbiased estimating
  // equation; its information is the covariance. One step suffices: the start is within a few
  // sigma, and the model's curvature moves the result by a small fraction of one.
  double i00 = 0.0, i01 = 0.0, i11 = 0.0, b0 = 0.0, b1 = 0.0;
  for (int i = 0; i < n; ++i) {
    const double r = ranges[i];
    if (!(r > 0.0)) continue;
    const double c = (points[i].x() * ca + points[i].y() * sa) / r;   // cos(phi_i - alpha)
    const double sn = (points[i].y() * ca - points[i].x() * sa) / r;  // sin(phi_i - alpha)
    if (c < 1e-3) return false;  // a beam (nearly) parallel to the line: no range model
    const double ic = 1.0 / c;
    const double v = range_var[i] + model_var * ic * ic;  // range variance
    const double wi = 1.0 / std::max(v, 1e-12);
    const double e = r - rho * ic;
    const double j0 = ic, j1 = -rho * sn * ic * ic;  // d(rho / c) / d(rho, alpha)
    i00 += wi * j0 * j0;
    i01 += wi * j0 * j1;
    i11 += wi * j1 * j1;
    b0 += wi * j0 * e;
    b1 += wi * j1 * e;
  }
  const double det = i00 * i11 - i01 * i01;
  if (!(det > 1e-300) || !std::isfinite(det)) return false;
  rho += (i11 * b0 - i01 * b1) / det;
  const double alpha = std::atan2(sa, ca) + (i00 * b1 - i01 * b0) / det;
  if (rho < 0.0) return false;
  ca = std::cos(alpha);
  sa = std::sin(alpha);
  line.rho = rho;
  line.alpha = WrapAngle(alpha);
  line.cov << i11 / det, -i01 / det, -i01 / det, i00 / det;
  const double ta = -points.front().x() * sa + points.front().y() * ca;
  const double tb = -points.back().x() * sa + points.back().y() * ca;
  line.endpoint_a = Vec2(rho * ca - ta * sa, rho * sa + ta * ca);
  line.endpoint_b = Vec2(rho * ca - tb * sa, rho * sa + tb * ca);
  line.num_points = n;
  return true;
}

}  // namespace

std::vector<ObservedLine> ExtractLines(const LaserScan& scan,
                                       const LineExtractionOptions& options) {
  std::vector<ObservedLine> lines;
  const int beams = static_cast<int>(scan.ranges.size());
  if (beams == 0) return lines;
  // Per-thread scratch: no heap allocation per scan once warm.
  thread_local Scratch scratch;
  std::vector<Vec2>& pts = scratch.pts;
  std::vector<double>& var = scratch.var;
  std::vector<double>& range = scratch.range;
  std::vector<int>& beam_of = scratch.beam_of;
  std::vector<Segment>& clusters = scratch.clusters;
  pts.clear();
  var.clear();
  range.clear();
  beam_of.clear();
  clusters.clear();
  const double max_range = scan.max_range > 0.0f ? scan.max_range : 1e30;
  const double max_gap2 = options.max_gap * options.max_gap;
  int cluster_begin = 0;
  // Beam directions by rotation recurrence (exact to ~1e-13 over a scan).
  const double inc = scan.angle_increment;
  const double c_inc = std::cos(inc), s_inc = std::sin(inc);
  double c_phi = std::cos(static_cast<double>(scan.angle_min));
  double s_phi = std::sin(static_cast<double>(scan.angle_min));
  for (int i = 0; i < beams; ++i) {
    const float r = scan.ranges[i];
    const double c = c_phi, sn = s_phi;
    c_phi = c * c_inc - sn * s_inc;
    s_phi = sn * c_inc + c * s_inc;
    if (!IsReturn(r) || r < options.min_range || r >= max_range) continue;
    const Vec2 p(r * c, r * sn);
    if (!pts.empty() && (p - pts.back()).squaredNorm() > max_gap2) {
      clusters.push_back({cluster_begin, static_cast<int>(pts.size())});
      cluster_begin = static_cast<int>(pts.size());
    }
    const double sigma = options.range_sigma + options.range_sigma_per_m * r;
    pts.push_back(p);
    var.push_back(sigma * sigma);
    range.push_back(r);
    beam_of.push_back(i);
  }
  if (!pts.empty()) clusters.push_back({cluster_begin, static_cast<int>(pts.size())});

  std::vector<Segment>& segments = scratch.segments;
  std::vector<Segment>& stack = scratch.stack;
  std::vector<Segment>& merged = scratch.merged;
  segments.clear();
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
    merged.clear();
    for (size_t i = first_of_cluster; i < segments.size(); ++i) {
      if (!merged.empty() &&
          MaxResidualTls(pts, merged.back().begin, segments[i].end) <= options.split_distance) {
        merged.back().end = segments[i].end;
      } else {
        merged.push_back(segments[i]);
      }
    }
    segments.resize(first_of_cluster);
    for (Segment& m : merged) {
      if (m.begin != cl.begin) m.begin += options.corner_points;
      if (m.end != cl.end) m.end -= options.corner_points;
      m.end = std::max(m.end, m.begin);
    }
    segments.insert(segments.end(), merged.begin(), merged.end());
  }

  const double model_var = options.model_sigma * options.model_sigma;
  const bool fit_gate_off = options.fit_gate >= 1.0;
  for (const Segment& s : segments) {
    if (s.end - s.begin < options.min_points) continue;
    // The fitted extent is the end points projected on the line: never longer than the chord.
    if ((pts[s.end - 1] - pts[s.begin]).squaredNorm() < options.min_length * options.min_length) {
      continue;
    }
    // Fit, then trim end points that do not belong to the line (the neighbour wall's points
    // near a corner, mixed pixels) and refit.
    int b = s.begin, e = s.end;
    ObservedLine line;
    bool ok = false;
    for (int round = 0; round < 6; ++round) {
      ok = FitLineRanged(std::span<const Vec2>(pts.data() + b, e - b), range.data() + b,
                         std::span<const double>(var.data() + b, e - b), model_var, line);
      if (!ok) break;
      const double ca = std::cos(line.alpha), sa = std::sin(line.alpha);
      // Squared normal residual of point i over its normal variance.
      const auto normalized = [&](int i) {
        const double proj = pts[i].x() * ca + pts[i].y() * sa;
        const double d = proj - line.rho;
        const double c2 = proj * proj / std::max(pts[i].squaredNorm(), 1e-12);
        return d * d / std::max(var[i] * c2 + model_var, 1e-12);
      };
      // Where the beams' spacing along the line nears max_gap, whether the gap test cut the
      // cluster depends on the range noise: the points kept there are a biased selection
      // (short ranges). End points whose spacing, rho dphi / cos^2(phi - alpha) from the fit
      // and the exact bearing, comes within 4 sigma of the spacing's noise (the range noise
      // along the line, sqrt(2) sigma_r |sin(phi - alpha)|) of max_gap are trimmed, so that
      // the cut is the fit's.
      const auto too_sparse = [&](int i) {
        const double inv_r = 1.0 / std::max(range[i], 1e-12);
        const double c = (pts[i].x() * ca + pts[i].y() * sa) * inv_r;
        const double sn = (pts[i].y() * ca - pts[i].x() * sa) * inv_r;
        const double margin = kSpacingMargin * std::sqrt(var[i]) * std::abs(sn);
        return c <= 0.0 || line.rho * std::abs(inc) > (options.max_gap - margin) * c * c;
      };
      const int b0 = b, e0 = e;
      while (e - b >= options.min_points && too_sparse(b)) ++b;
      while (e - b >= options.min_points && too_sparse(e - 1)) --e;
      if (e - b < options.min_points) {
        ok = false;
        break;
      }
      while (e - b > options.min_points && normalized(b) > 9.0) ++b;
      while (e - b > options.min_points && normalized(e - 1) > 9.0) --e;
      if (b != b0 || e != e0) {
        ok = false;  // refit
        continue;
      }
      if (fit_gate_off) break;
      // In a short segment one stray end point pulls the fit towards itself and hides its own
      // residual: test each end point against the fit of the others (deletion residual).
      if (e - b <= 3 * options.min_points) {
        bool stray = false;
        for (const int i : {b, e - 1}) {
          const int ob = i == b ? b + 1 : b, oe = i == b ? e : e - 1;
          ObservedLine others;
          if (!FitLineRanged(std::span<const Vec2>(pts.data() + ob, oe - ob), range.data() + ob,
                             std::span<const double>(var.data() + ob, oe - ob), model_var,
                             others)) {
            continue;
          }
          const double co = std::cos(others.alpha), so = std::sin(others.alpha);
          const double proj = pts[i].x() * co + pts[i].y() * so;
          const double c2 = proj * proj / std::max(pts[i].squaredNorm(), 1e-12);
          const Eigen::RowVector2d j(-1.0, -pts[i].x() * so + pts[i].y() * co);
          const double v = var[i] * c2 + model_var + j * others.cov * j.transpose();
          const double d = proj - others.rho;
          if (d * d > 9.0 * v) {
            stray = true;
            if (i == b) {
              ++b;
            } else {
              --e;
            }
            break;
          }
        }
        if (stray) {
          ok = false;
          if (e - b < options.min_points) break;
          continue;
        }
      }
      // Goodness of fit: the weighted squared residuals of points of one straight wall are
      // chi-square with n - 2 dof. A segment that fails (points of a neighbouring wall at a
      // corner or door jamb that trimming could not remove, seen at a grazing angle) is not a
      // line: its covariance would be a lie.
      double chi2 = 0.0;
      for (int i = b; i < e; ++i) chi2 += normalized(i);
      if (!(chi2 <= ChiSquareQuantile(options.fit_gate, e - b - 2))) ok = false;
      break;
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
