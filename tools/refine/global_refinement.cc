#include "tools/refine/global_refinement.h"

#include <ceres/ceres.h>

#include <Eigen/Cholesky>
#include <array>
#include <cmath>

#include "core/atlas/dijkstra_projection.h"

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

  const Projection projection = DijkstraProjection(graph, 0);
  std::vector<std::array<double, 3>> x(static_cast<size_t>(n));
  std::vector<uint8_t> placed(static_cast<size_t>(n), 0);
  for (const ProjectedFrame& f : projection.entries) {
    const Pose2& p = f.pose.mean;
    x[static_cast<size_t>(f.frame)] = {p.x, p.y, p.theta};
    placed[static_cast<size_t>(f.frame)] = 1;
    result.initial[static_cast<size_t>(f.frame)] = p;
  }
  result.frames = static_cast<int>(projection.entries.size());

  ceres::Problem problem;
  for (const AtlasEdge& e : graph.Edges()) {
    if (!placed[static_cast<size_t>(e.a)] || !placed[static_cast<size_t>(e.b)]) continue;
    Mat3 cov = 0.5 * (e.b_in_a.cov + e.b_in_a.cov.transpose());
    for (int i = 0; i < 3; ++i) cov(i, i) = std::max(cov(i, i), options.min_variance);
    // Information^(1/2): L^T with L L^T = information, so |L^T e|^2 = e^T info e.
    const Mat3 info = cov.inverse();
    Eigen::LLT<Mat3> llt(0.5 * (info + info.transpose()));
    if (llt.info() != Eigen::Success) {
      cov += Mat3::Identity() * options.min_variance * 1e3;
      llt.compute(cov.inverse());
      if (llt.info() != Eigen::Success) continue;
    }
    const Mat3 sqrt_info = llt.matrixL().transpose();
    problem.AddResidualBlock(new ceres::AutoDiffCostFunction<EdgeResidual, 3, 3, 3>(
                                 new EdgeResidual(e.b_in_a.mean, sqrt_info)),
                             nullptr, x[static_cast<size_t>(e.a)].data(),
                             x[static_cast<size_t>(e.b)].data());
    ++result.edges;
  }
  if (result.edges == 0) {
    result.status = RefineStatus::kConverged;
    result.refined = result.initial;
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
    result.refined[static_cast<size_t>(f)] = Pose2{v[0], v[1], WrapAngle(v[2])};
  }
  return result;
}

}  // namespace atlas::refine
