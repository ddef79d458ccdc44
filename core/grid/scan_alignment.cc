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

// The information of the scan's surfaces (Censi 2007, point-to-line): every point of `points`
// (scan order) explained by `map` at `x` (probability at least 0.5) whose neighbours within
// `radius` (up to 3 either side in sequence) lie on a line contributes j j^T with
// j = (n, n . d(T_x q)/d theta), n the line's normal; a point whose neighbours do not lie on a
// line (a corner, a chair leg) contributes its translation and rotation in every direction
// (half of each); a point without two such neighbours, nothing.
constexpr int kNeighbours = 6;

Mat3 SurfaceInformation(const InterpolatedGrid& map, const std::vector<Vec2>& points,
                        const Pose2& x, double radius, double max_flatness) {
  const RigidTransform t(x);
  Mat3 info = Mat3::Zero();
  const int n = static_cast<int>(points.size());
  for (int i = 0; i < n; ++i) {
    const Vec2& q = points[i];
    if (map.Evaluate(t.Apply(q), nullptr) < 0.5) continue;
    Vec2 mean = Vec2::Zero();
    int count = 0;
    for (int j = std::max(0, i - kNeighbours); j <= std::min(n - 1, i + kNeighbours); ++j) {
      if ((points[j] - q).norm() > radius) continue;
      mean += points[j];
      ++count;
    }
    if (count < 3) continue;
    mean /= count;
    Eigen::Matrix2d scatter = Eigen::Matrix2d::Zero();
    for (int j = std::max(0, i - kNeighbours); j <= std::min(n - 1, i + kNeighbours); ++j) {
      if ((points[j] - q).norm() > radius) continue;
      scatter += (points[j] - mean) * (points[j] - mean).transpose();
    }
    const Eigen::SelfAdjointEigenSolver<Eigen::Matrix2d> line(scatter);
    const Vec2 d_theta(-t.s * q.x() - t.c * q.y(), t.c * q.x() - t.s * q.y());
    if (line.eigenvalues()(0) <= max_flatness * line.eigenvalues()(1)) {
      const Vec2 n0 = line.eigenvectors().col(0);
      const Vec2 normal(t.c * n0.x() - t.s * n0.y(), t.s * n0.x() + t.c * n0.y());
      const Vec3 j(normal.x(), normal.y(), normal.dot(d_theta));
      info += j * j.transpose();
    } else {
      for (const Vec2& normal : {Vec2(1.0, 0.0), Vec2(0.0, 1.0)}) {
        const Vec3 j(normal.x(), normal.y(), normal.dot(d_theta));
        info += 0.5 * j * j.transpose();
      }
    }
  }
  return info;
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
                                     const Pose2& initial, AlignmentResult* out) {
  const double r = grid.limits().resolution;
  const SearchWindow window =
      MakeSearchWindow(options_.linear_window, options_.angular_window, r,
                       AngularSearchStep(points, r, options_.min_angular_step));
  DiscretizeScans(grid.limits(), points, initial, window, &scans_);
  // Ranked by the sum of stored values, unknown counted as 1: the probability is affine in the
  // value and an unknown cell has the probability of value 1.
  const std::vector<uint16_t>& values = grid.values();
  const GridLimits& l = grid.limits();
  Placement best;
  int64_t best_sum = -1;
  long best_distance = 0;
  const int span = 2 * window.linear_cells + 1;
  row_sums_.resize(static_cast<size_t>(span));
  for (int h = 0; h < window.headings(); ++h) {
    const CellIndex* cells = scans_.Heading(h);
    for (int y = -window.linear_cells; y <= window.linear_cells; ++y) {
      // The sums of one row of placements, a point at a time: a point whose row of cells lies
      // in the grid adds a run of consecutive values.
      std::fill(row_sums_.begin(), row_sums_.end(), 0);
      int64_t* sums = row_sums_.data();
      for (int i = 0; i < scans_.points; ++i) {
        const CellIndex first{cells[i].x - window.linear_cells, cells[i].y + y};
        if (first.y >= 0 && first.y < l.height && first.x >= 0 && first.x + span <= l.width) {
          const uint16_t* row = values.data() + l.IndexOf(first);
          for (int k = 0; k < span; ++k) sums[k] += std::max<uint16_t>(row[k], 1);
        } else {
          for (int k = 0; k < span; ++k) {
            const CellIndex c{first.x + k, first.y};
            sums[k] += l.Contains(c) ? std::max<uint16_t>(values[l.IndexOf(c)], 1) : 1;
          }
        }
      }
      for (int x = -window.linear_cells; x <= window.linear_cells; ++x) {
        const int64_t sum = sums[x + window.linear_cells];
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
  out->correlative_score =
      grid.ProbabilityOfValue(0) +
      (grid.ProbabilityOfValue(ProbabilityGrid::kMaxValue) - grid.ProbabilityOfValue(0)) *
          (static_cast<double>(best_sum) / scans_.points - 1.0) / (ProbabilityGrid::kMaxValue - 1);
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

  out.surface_information = SurfaceInformation(map, points, x, options_.normal_radius, 0.2);
  const Eigen::SelfAdjointEigenSolver<Mat3> eigen(s_diagonal * out.surface_information *
                                                  s_diagonal);
  const Vec3 strengths = eigen.eigenvalues();  // ascending
  Mat3 keep = Mat3::Identity();
  Mat3 free_part = Mat3::Zero();
  for (int i = 0; i < 3; ++i) {
    if (strengths(i) > options_.degenerate_ratio * strengths(2) && strengths(i) > 0.0) continue;
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
