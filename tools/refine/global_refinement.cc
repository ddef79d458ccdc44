#include "tools/refine/global_refinement.h"

#include <ceres/ceres.h>

#include <Eigen/Cholesky>
#include <array>
#include <cmath>

#include "core/atlas/dijkstra_projection.h"
#include "core/atlas/frame_components.h"
#include "core/geometry/covariance.h"

namespace atlas::refine {
namespace {

template <typename T>
T Wrap(const T& a) {
  // (-pi, pi]; ceres::floor is defined for Jets.
  const T two_pi(2.0 * M_PI);
  return a - two_pi * ceres::floor((a + T(M_PI)) / two_pi);
}

struct EdgeResidual {
  EdgeResidual(const Pose2& b_in_a, const Mat3& sqrt_information)
      : m(b_in_a), w(sqrt_information) {}

  template <typename T>
  bool operator()(const T* xa, const T* xb, T* residual) const {
    const T c = ceres::cos(xa[2]), s = ceres::sin(xa[2]);
    const T dx = xb[0] - xa[0], dy = xb[1] - xa[1];
    T e[3];
    e[0] = c * dx + s * dy - T(m.x);
    e[1] = -s * dx + c * dy - T(m.y);
    e[2] = Wrap(xb[2] - xa[2] - T(m.theta));
    for (int i = 0; i < 3; ++i)
      residual[i] = T(w(i, 0)) * e[0] + T(w(i, 1)) * e[1] + T(w(i, 2)) * e[2];
    return true;
  }

  Pose2 m;
  Mat3 w;
};

}  // namespace

std::string RefineOptions::Validate() const {
  if (max_iterations < 1) return "max_iterations must be >= 1";
  if (!(function_tolerance > 0.0)) return "function_tolerance must be > 0";
  if (!(min_variance > 0.0)) return "min_variance must be > 0";
  return "";
}

const char* ToString(RefineStatus s) {
  switch (s) {
    case RefineStatus::kConverged:
      return "converged";
    case RefineStatus::kNoConvergence:
      return "no convergence";
    case RefineStatus::kNoFrames:
      return "no frames";
    case RefineStatus::kFailed:
      return "failed";
  }
  return "unknown";
}

RefineResult RefineGlobal(const AtlasGraph& graph, const RefineOptions& options) {
  RefineResult result;
  const int n = graph.FrameCount();
  result.initial.assign(static_cast<size_t>(n), std::nullopt);
  result.refined.assign(static_cast<size_t>(n), std::nullopt);
  if (n == 0) return result;

  // The usable constraints: an edge whose covariance is not finite, has a negative variance, or
  // is not positive definite once symmetrised and floored cannot weigh a residual; it is left
  // out and counted.
  struct Constraint {
    FrameId a, b;
    Pose2 b_in_a;
    Mat3 sqrt_info;
  };
  std::vector<Constraint> constraints;
  for (const AtlasEdge& e : graph.Edges()) {
    if (e.a < 0 || e.b < 0 || e.a >= n || e.b >= n) continue;
    Mat3 cov = 0.5 * (e.b_in_a.cov + e.b_in_a.cov.transpose());
    bool usable = cov.allFinite() && cov.diagonal().minCoeff() >= 0.0;
    if (usable) {
      for (int i = 0; i < 3; ++i) cov(i, i) = std::max(cov(i, i), options.min_variance);
      usable = IsPositiveDefiniteCovariance(cov);
    }
    std::optional<Mat3> sqrt_info;
    if (usable) {
      // Information^(1/2): L^T with L L^T = information, so |L^T e|^2 = e^T info e.
      const Mat3 info = cov.inverse();
      Eigen::LLT<Mat3> llt(0.5 * (info + info.transpose()));
      if (llt.info() == Eigen::Success && llt.matrixL().toDenseMatrix().allFinite())
        sqrt_info = llt.matrixL().transpose();
    }
    if (!sqrt_info) {
      ++result.skipped_edges;
      continue;
    }
    constraints.push_back({e.a, e.b, e.b_in_a.mean, *sqrt_info});
  }

  // The frames reached from frame 0 through usable constraints; the initial arrangement is the
  // Dijkstra projection from frame 0.
  FrameComponents reach;
  for (int f = 0; f < n; ++f) reach.AddFrame();
  for (const Constraint& c : constraints) reach.Join(c.a, c.b);
  std::vector<uint8_t> placed(static_cast<size_t>(n), 0);
  for (FrameId f = 0; f < n; ++f) placed[static_cast<size_t>(f)] = reach.Connected(f, 0);
  std::vector<std::array<double, 3>> x(static_cast<size_t>(n));
  std::vector<uint8_t> started(static_cast<size_t>(n), 0);  // x holds an initial value
  for (const ProjectedFrame& f : DijkstraProjection(graph, 0).entries) {
    const Pose2& p = f.pose.mean;
    if (f.frame < 0 || f.frame >= n || !placed[static_cast<size_t>(f.frame)] || !p.IsFinite())
      continue;
    x[static_cast<size_t>(f.frame)] = {p.x, p.y, p.theta};
    started[static_cast<size_t>(f.frame)] = 1;
  }
  x[0] = {0.0, 0.0, 0.0};
  started[0] = 1;
  // A reached frame the projection did not place starts where a usable constraint puts it.
  for (bool grew = true; grew;) {
    grew = false;
    const auto start = [&](FrameId from, FrameId to, const Pose2& to_in_from) {
      if (!started[static_cast<size_t>(from)] || started[static_cast<size_t>(to)]) return;
      const auto& v = x[static_cast<size_t>(from)];
      const Pose2 p = Compose(Pose2{v[0], v[1], v[2]}, to_in_from);
      x[static_cast<size_t>(to)] = {p.x, p.y, p.theta};
      started[static_cast<size_t>(to)] = 1;
      grew = true;
    };
    for (const Constraint& c : constraints) {
      start(c.a, c.b, c.b_in_a);
      start(c.b, c.a, Inverse(c.b_in_a));
    }
  }
  for (int f = 0; f < n; ++f) {
    if (!placed[static_cast<size_t>(f)]) {
      ++result.unreached;
      continue;
    }
    const auto& v = x[static_cast<size_t>(f)];
    result.initial[static_cast<size_t>(f)] = Pose2{v[0], v[1], v[2]};
    ++result.frames;
  }

  ceres::Problem problem;
  for (const Constraint& c : constraints) {
    if (!placed[static_cast<size_t>(c.a)] || !placed[static_cast<size_t>(c.b)]) continue;
    problem.AddResidualBlock(new ceres::AutoDiffCostFunction<EdgeResidual, 3, 3, 3>(
                                 new EdgeResidual(c.b_in_a, c.sqrt_info)),
                             nullptr, x[static_cast<size_t>(c.a)].data(),
                             x[static_cast<size_t>(c.b)].data());
    ++result.edges;
  }
  if (result.edges == 0) {
    // Frame 0 alone.
    result.status = RefineStatus::kConverged;
    result.refined = result.initial;
    return result;
  }
  // Every constraint added joins frames reached from frame 0, so frame 0 has a block.
  if (!problem.HasParameterBlock(x[0].data())) {
    result.status = RefineStatus::kFailed;
    result.message = "frame 0 has no usable constraint";
    return result;
  }
  problem.SetParameterBlockConstant(x[0].data());

  ceres::Solver::Options solver;
  solver.linear_solver_type = ceres::SPARSE_NORMAL_CHOLESKY;
  solver.max_num_iterations = options.max_iterations;
  solver.function_tolerance = options.function_tolerance;
  solver.gradient_tolerance = 1e-14;
  solver.parameter_tolerance = 1e-12;
  solver.num_threads = 1;
  solver.logging_type = ceres::SILENT;
  ceres::Solver::Summary summary;
  ceres::Solve(solver, &problem, &summary);
  result.initial_cost = summary.initial_cost;
  result.final_cost = summary.final_cost;
  result.iterations = static_cast<int>(summary.iterations.size());
  result.message = summary.BriefReport();
  if (summary.termination_type == ceres::CONVERGENCE) {
    result.status = RefineStatus::kConverged;
  } else if (summary.termination_type == ceres::NO_CONVERGENCE) {
    result.status = RefineStatus::kNoConvergence;
  } else {
    result.status = RefineStatus::kFailed;
    return result;
  }
  for (int f = 0; f < n; ++f) {
    if (!placed[static_cast<size_t>(f)]) continue;
    const auto& v = x[static_cast<size_t>(f)];
    if (!std::isfinite(v[0]) || !std::isfinite(v[1]) || !std::isfinite(v[2])) {
      result.status = RefineStatus::kFailed;
      result.message = "the solution is not finite: " + result.message;
      result.refined.assign(static_cast<size_t>(n), std::nullopt);
      return result;
    }
    result.refined[static_cast<size_t>(f)] = Pose2{v[0], v[1], WrapAngle(v[2])};
  }
  return result;
}

}  // namespace atlas::refine
