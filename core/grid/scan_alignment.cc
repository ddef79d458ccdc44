#include "core/grid/scan_alignment.h"

#include <Eigen/Cholesky>
#include <Eigen/Eigenvalues>
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
                                     const Pose2& initial, double* score) {
  const double r = grid.limits().resolution;
  const SearchWindow window =
      MakeSearchWindow(options_.linear_window, options_.angular_window, r,
                       AngularSearchStep(points, r, options_.min_angular_step));
  DiscretizeScans(grid.limits(), points, initial, window, &scans_);
  Placement best;
  double best_sum = -1.0;
  long best_distance = 0;
  for (int h = 0; h < window.headings(); ++h) {
    const CellIndex* cells = scans_.Heading(h);
    for (int y = -window.linear_cells; y <= window.linear_cells; ++y) {
      for (int x = -window.linear_cells; x <= window.linear_cells; ++x) {
        double sum = 0.0;
        for (int i = 0; i < scans_.points; ++i) {
          sum += grid.Probability(CellIndex{cells[i].x + x, cells[i].y + y});
        }
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
  *score = best_sum / static_cast<double>(points.size());
  return PlacementPose(best, initial, window, r);
}

AlignmentResult ScanAligner::Align(const ProbabilityGrid& grid, const std::vector<Vec2>& points,
                                   const Pose2& initial) {
  AlignmentResult out;
  out.pose.mean = initial;
  out.points = static_cast<int>(points.size());
  if (out.points < options_.min_points) return out;
  Pose2 x = CorrelativeSearch(grid, points, initial, &out.correlative_score);
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
    const bool small = delta.norm() < options_.convergence_step;
    if (next_cost < cost) {
      x = next;
      lambda *= 0.1;
      cost = Evaluate(map, points, x, &h, &g);
    } else {
      lambda *= 10.0;
    }
    if (small) break;
  }

  // Covariance in (x, y, L theta): S maps those coordinates back to (x, y, theta).
  double radius_squared = 0.0;
  for (const Vec2& q : points) radius_squared += q.squaredNorm();
  out.radius = std::max(0.1, std::sqrt(radius_squared / out.points));
  const Vec3 s_diagonal(1.0, 1.0, 1.0 / out.radius);
  const double n = static_cast<double>(out.points);
  const double s2 =
      std::max(cost / (n - 3.0), options_.min_residual_sigma * options_.min_residual_sigma);
  out.information = h / s2;
  const Mat3 scaled_h = s_diagonal.asDiagonal() * h * s_diagonal.asDiagonal();
  const Eigen::SelfAdjointEigenSolver<Mat3> eigen(scaled_h);
  const Vec3 lambdas = eigen.eigenvalues();  // ascending
  Vec3 variances;
  for (int i = 2; i >= 0; --i) {
    if (lambdas(i) > options_.degenerate_ratio * lambdas(2) && lambdas(i) > 0.0) {
      variances(i) = s2 / lambdas(i);
    } else {
      variances(i) = options_.unconstrained_sigma * options_.unconstrained_sigma;
      out.unconstrained_directions.col(out.unconstrained++) = eigen.eigenvectors().col(i);
    }
  }
  const Mat3 scaled_cov =
      eigen.eigenvectors() * variances.asDiagonal() * eigen.eigenvectors().transpose();
  out.pose.mean = x;
  out.pose.cov = s_diagonal.asDiagonal() * scaled_cov * s_diagonal.asDiagonal();
  double sum = 0.0;
  const RigidTransform t(x);
  for (const Vec2& q : points) sum += map.Evaluate(t.Apply(q), nullptr);
  out.score = sum / n;
  out.outcome =
      out.unconstrained > 0 ? AlignmentOutcome::kUnconstrained : AlignmentOutcome::kAligned;
  return out;
}

}  // namespace atlas
