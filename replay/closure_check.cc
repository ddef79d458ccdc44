#include "replay/closure_check.h"

#include <Eigen/Cholesky>
#include <algorithm>
#include <cmath>
#include <cstdio>

namespace atlas::replay {

std::string ClosureCheckOptions::Validate() const {
  if (!(chi2_threshold > 0.0)) return "chi2_threshold must be > 0";
  if (!(axis_sigmas > 0.0)) return "axis_sigmas must be > 0";
  if (!(gross_translation_m > 0.0) || !(gross_rotation_deg > 0.0))
    return "gross error thresholds must be > 0";
  return "";
}

ClosureVerdict CheckClosure(const AtlasEdge& edge, const Pose2& reference_a,
                            const Pose2& reference_b, const ClosureCheckOptions& options) {
  ClosureVerdict v;
  v.a = edge.a;
  v.b = edge.b;
  v.kind = edge.kind;
  v.estimate = edge.b_in_a.mean;
  v.reference = Between(reference_a, reference_b);
  v.error = Vec3(v.estimate.x - v.reference.x, v.estimate.y - v.reference.y,
                 WrapAngle(v.estimate.theta - v.reference.theta));
  // A floor keeps a degenerate covariance from dividing by zero; it is far below any real
  // edge's uncertainty (1e-6 m, 1e-6 rad).
  const Mat3 cov = edge.b_in_a.cov + Mat3::Identity() * 1e-12;
  v.d2 = v.error.dot(cov.ldlt().solve(v.error));
  for (int i = 0; i < 3; ++i)
    v.worst_axis_sigmas =
        std::max(v.worst_axis_sigmas, std::abs(v.error[i]) / std::sqrt(cov(i, i)));
  v.false_chi2 = !(v.d2 <= options.chi2_threshold);
  v.false_axis = !(v.worst_axis_sigmas <= options.axis_sigmas);
  v.gross = std::hypot(v.error[0], v.error[1]) > options.gross_translation_m ||
            std::abs(v.error[2]) * 180.0 / M_PI > options.gross_rotation_deg;
  return v;
}

ClosureReport CheckClosures(const AtlasGraph& graph,
                            const std::vector<std::optional<Pose2>>& origin_reference,
                            const ClosureCheckOptions& options) {
  ClosureReport report;
  const auto ref_of = [&](FrameId f) -> const std::optional<Pose2>* {
    if (f < 0 || static_cast<size_t>(f) >= origin_reference.size()) return nullptr;
    return origin_reference[static_cast<size_t>(f)].has_value() ? &origin_reference[f] : nullptr;
  };
  for (const AtlasEdge& edge : graph.Edges()) {
    if (edge.origin != EdgeKind::kMapMatch) continue;
    ++report.map_match_edges;
    const auto* ra = ref_of(edge.a);
    const auto* rb = ref_of(edge.b);
    if (ra == nullptr || rb == nullptr) {
      ++report.unreferenced;
      continue;
    }
    const ClosureVerdict v = CheckClosure(edge, **ra, **rb, options);
    report.false_chi2 += v.false_chi2;
    report.false_axis += v.false_axis;
    report.gross += v.gross;
    report.edges.push_back(v);
  }
  return report;
}

std::string FormatClosures(const ClosureReport& report) {
  std::string t =
      "# atlas-replay closures: from to kind x y theta ref_x ref_y ref_theta err_xy_m err_deg "
      "d2 worst_axis_sigmas false_chi2 false_axis gross\n";
  char buf[400];
  for (const ClosureVerdict& v : report.edges) {
    std::snprintf(
        buf, sizeof buf,
        "%d\t%d\t%s\t%.6f\t%.6f\t%.6f\t%.6f\t%.6f\t%.6f\t%.4f\t%.3f\t%.4g\t%.3g\t%d\t%d\t%d\n", v.a,
        v.b, EdgeKindName(v.kind), v.estimate.x, v.estimate.y, v.estimate.theta, v.reference.x,
        v.reference.y, v.reference.theta, std::hypot(v.error[0], v.error[1]),
        std::abs(v.error[2]) * 180.0 / M_PI, v.d2, v.worst_axis_sigmas, v.false_chi2 ? 1 : 0,
        v.false_axis ? 1 : 0, v.gross ? 1 : 0);
    t += buf;
  }
  return t;
}

}  // namespace atlas::replay
