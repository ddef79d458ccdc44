#include "core/grid/scan_alignment.h"

#include <Eigen/Cholesky>
#include <Eigen/Eigenvalues>
#include <Eigen/QR>
#include <algorithm>
#include <cassert>
#include <cmath>

#include "core/grid/interpolated_grid.h"

namespace atlas {
namespace {

// Sum of squared residuals 1 - M(T_x q_i) and, when `h` is not null, the Gauss-Newton H = J^T J
// and g = J^T r.
double Evaluate(const InterpolatedGrid& map, const std::vector<Vec2>& points, const Pose2& x,
                Mat3* h, Vec3* g) {
  const RigidTransform t(x);
  double cost = 0.0;
  if (h != nullptr) {
    h->setZero();
    g->setZero();
  }
  for (const Vec2& q : points) {
    Vec2 gradient;
    const double r = 1.0 - map.Evaluate(t.Apply(q), h != nullptr ? &gradient : nullptr);
    cost += r * r;
    if (h == nullptr) continue;
    // d(T_x q)/d(theta) = (-s qx - c qy, c qx - s qy); dr = -grad . d(T_x q).
    const Vec2 d_theta(-t.s * q.x() - t.c * q.y(), t.c * q.x() - t.s * q.y());
    const Vec3 j(-gradient.x(), -gradient.y(), -gradient.dot(d_theta));
    *h += j * j.transpose();
    *g += j * r;
  }
  return cost;
}

// -d^2 s / dd^2 of the quadratic fitted by least squares to the scores of the placements of
// `window` (heading, y, x order) within `cells` cells and `steps` heading steps of `best`,
// d = (x, y, theta) relative to `best`.
Mat3 ResponseCurvature(const std::vector<double>& scores, const SearchWindow& window,
                       const Placement& best, int cells, int steps, double resolution) {
  using Vec10 = Eigen::Matrix<double, 10, 1>;
  Eigen::Matrix<double, 10, 10> normal = Eigen::Matrix<double, 10, 10>::Zero();
  Vec10 rhs = Vec10::Zero();
  size_t i = 0;
  for (int h = 0; h < window.headings(); ++h) {
    for (int y = -window.linear_cells; y <= window.linear_cells; ++y) {
      for (int x = -window.linear_cells; x <= window.linear_cells; ++x, ++i) {
        // In cells and heading steps, so that the system is well scaled.
        const double a = x - best.x, b = y - best.y, c = h - best.heading;
        if (std::abs(a) > cells || std::abs(b) > cells || std::abs(c) > steps) continue;
        Vec10 f;
        f << 1.0, a, b, c, 0.5 * a * a, 0.5 * b * b, 0.5 * c * c, a * b, a * c, b * c;
        normal += f * f.transpose();
        rhs += f * scores[i];
      }
    }
  }
  // Directions the window does not span (one heading, no translation) have no curvature.
  normal.diagonal() += Vec10::Constant(1e-9 * normal.trace());
  const Vec10 q = normal.ldlt().solve(rhs);
  Mat3 hessian;
  hessian << q(4), q(7), q(8), q(7), q(5), q(9), q(8), q(9), q(6);
  const Vec3 unit(1.0 / resolution, 1.0 / resolution, 1.0 / window.angular_step);
  return -(unit.asDiagonal() * hessian * unit.asDiagonal());
}

// Half-width of the response curvature's fit, cells; in heading, the steps that move a point
// at the rms radius as far. Narrower, the cell-scale texture of the grid dominates the fit.
constexpr int kCurvatureCells = 2;

}  // namespace

const char* ToString(AlignmentOutcome o) {
  switch (o) {
    case AlignmentOutcome::kAligned:
      return "aligned";
    case AlignmentOutcome::kUnconstrained:
      return "unconstrained";
    case AlignmentOutcome::kTooFewPoints:
      return "too_few_points";
    case AlignmentOutcome::kLowScore:
      return "low_score";
  }
  return "?";
}

ScanAligner::ScanAligner(const ScanAlignmentOptions& options) : options_(options) {
  assert(options_.Validate().empty());
}

Pose2 ScanAligner::CorrelativeSearch(const ProbabilityGrid& grid, const std::vector<Vec2>& points,
                                     const Pose2& initial, AlignmentResult* out) {
  const double r = grid.limits().resolution;
  const SearchWindow window =
      MakeSearchWindow(options_.linear_window, options_.angular_window, r,
                       AngularSearchStep(points, r, options_.min_angular_step));
  DiscretizeScans(grid.limits(), points, initial, window, &scans_);
  scores_.clear();
  // Ranked by the sum of stored values, unknown counted as 1: the probability is affine in the
  // value and an unknown cell has the probability of value 1.
  const std::vector<uint16_t>& values = grid.values();
  const GridLimits& l = grid.limits();
  Placement best;
  int64_t best_sum = -1;
  long best_distance = 0;
  for (int h = 0; h < window.headings(); ++h) {
    const CellIndex* cells = scans_.Heading(h);
    for (int y = -window.linear_cells; y <= window.linear_cells; ++y) {
      for (int x = -window.linear_cells; x <= window.linear_cells; ++x) {
        int64_t sum = 0;
        for (int i = 0; i < scans_.points; ++i) {
          const CellIndex c{cells[i].x + x, cells[i].y + y};
          sum += l.Contains(c) ? std::max<uint16_t>(values[l.IndexOf(c)], 1) : 1;
        }
        scores_.push_back(
            grid.ProbabilityOfValue(0) +
            (grid.ProbabilityOfValue(ProbabilityGrid::kMaxValue) - grid.ProbabilityOfValue(0)) *
                (static_cast<double>(sum) / scans_.points - 1.0) /
                (ProbabilityGrid::kMaxValue - 1));
        const int dh = h - window.angular_steps;
        const long distance = static_cast<long>(x) * x + y * y + dh * dh;
        if (sum > best_sum || (sum == best_sum && distance < best_distance)) {
          best_sum = sum;
          best_distance = distance;
          best = Placement{h, x, y};
        }
      }
    }
  }
  out->correlative_score = *std::max_element(scores_.begin(), scores_.end());
  const int steps = std::max(
      1, static_cast<int>(std::lround(kCurvatureCells * r / (out->radius * window.angular_step))));
  out->response_curvature = ResponseCurvature(scores_, window, best, kCurvatureCells, steps, r);
  return PlacementPose(best, initial, window, r);
}

AlignmentResult ScanAligner::Align(const ProbabilityGrid& grid, const std::vector<Vec2>& points,
                                   const Pose2& initial) {
  AlignmentResult out;
  out.pose.mean = initial;
  out.points = static_cast<int>(points.size());
  if (out.points < options_.min_points) return out;
  // (x, y, L theta) compares metres and radians; S maps it back to (x, y, theta).
  double radius_squared = 0.0;
  for (const Vec2& q : points) radius_squared += q.squaredNorm();
  out.radius = std::max(0.1, std::sqrt(radius_squared / out.points));
  const Eigen::DiagonalMatrix<double, 3> s_diagonal(1.0, 1.0, 1.0 / out.radius);

  Pose2 x = CorrelativeSearch(grid, points, initial, &out);
  if (out.correlative_score < options_.min_score) {
    out.outcome = AlignmentOutcome::kLowScore;
    return out;
  }

  const InterpolatedGrid map(grid);
  Mat3 h;
  Vec3 g;
  double cost = Evaluate(map, points, x, &h, &g);
  double lambda = 1e-3;
  while (out.iterations < options_.max_iterations && lambda < 1e8) {
    ++out.iterations;
    Mat3 a = h;
    a.diagonal() += lambda * h.diagonal() + Vec3::Constant(1e-12 * h.trace() + 1e-15);
    const Vec3 delta = -a.ldlt().solve(g);
    const Pose2 next{x.x + delta.x(), x.y + delta.y(), WrapAngle(x.theta + delta.z())};
    const double next_cost = Evaluate(map, points, next, nullptr, nullptr);
    bool converged = delta.norm() < options_.convergence_step;
    if (next_cost < cost) {
      converged = converged || cost - next_cost < 1e-9 * cost;
      x = next;
      lambda = std::max(1e-9, 0.1 * lambda);
      cost = Evaluate(map, points, x, &h, &g);
    } else {
      lambda *= 10.0;
    }
    if (converged) break;
  }

  const double n = static_cast<double>(out.points);
  const double s2 =
      std::max(cost / (n - 3.0), options_.min_residual_sigma * options_.min_residual_sigma);
  out.information = h / s2;
  Mat3 scaled_cov =
      s2 * (s_diagonal * h * s_diagonal).completeOrthogonalDecomposition().pseudoInverse();

  const Eigen::SelfAdjointEigenSolver<Mat3> eigen(s_diagonal * out.response_curvature * s_diagonal);
  const Vec3 curvatures = eigen.eigenvalues();  // ascending
  Mat3 keep = Mat3::Identity();
  Mat3 free_part = Mat3::Zero();
  for (int i = 0; i < 3; ++i) {
    if (curvatures(i) > options_.degenerate_ratio * curvatures(2) && curvatures(i) > 0.0) continue;
    const Vec3 v = eigen.eigenvectors().col(i);
    out.unconstrained_directions.col(out.unconstrained++) = v;
    keep -= v * v.transpose();
    free_part += options_.unconstrained_sigma * options_.unconstrained_sigma * v * v.transpose();
  }
  scaled_cov = keep * scaled_cov * keep + free_part;
  out.pose.mean = x;
  out.pose.cov = s_diagonal * scaled_cov * s_diagonal;
  double sum = 0.0;
  const RigidTransform t(x);
  for (const Vec2& q : points) sum += map.Evaluate(t.Apply(q), nullptr);
  out.score = sum / n;
  out.outcome =
      out.unconstrained > 0 ? AlignmentOutcome::kUnconstrained : AlignmentOutcome::kAligned;
  return out;
}

}  // namespace atlas
