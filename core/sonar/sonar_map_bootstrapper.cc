#include "core/sonar/sonar_map_bootstrapper.h"

#include <Eigen/Cholesky>
#include <Eigen/Eigenvalues>
#include <Eigen/LU>
#include <algorithm>
#include <cassert>
#include <cmath>
#include <utility>

#include "core/localmap/jcbb.h"
#include "core/localmap/line_ekf_map.h"
#include "core/localmap/line_model.h"
#include "core/sonar/sonar_geometry.h"
#include "core/sonar/sonar_local_map.h"

namespace atlas {
namespace {

// A usable return of Z: the reading it belongs to, its transducer (cone scaled as the map
// interprets it), range and range variance.
struct UsableReturn {
  int reading = 0;
  SonarTransducer mount;
  double range = 0.0;
  double var = 0.0;
};

using Pairing = std::vector<std::pair<int, int>>;  // (return, line), in return order

enum class GaussNewton { kConverged, kSingular, kNotConverged };

}  // namespace

std::string SonarBootstrapOptions::Validate() const {
  if (min_returns < 3) return "min_returns must be at least 3";
  if (!(max_sigma_xy > 0)) return "max_sigma_xy must be positive";
  if (!(max_sigma_theta > 0)) return "max_sigma_theta must be positive";
  if (!(residual_gate > 0 && residual_gate < 1)) return "residual_gate must lie in (0, 1)";
  if (rounds < 1) return "rounds must be at least 1";
  if (max_iterations < 1) return "max_iterations must be at least 1";
  return "";
}

SonarMapBootstrapper::SonarMapBootstrapper(const SonarBootstrapOptions& options) : o_(options) {
  assert(o_.Validate().empty());
}

SonarBootstrapResult SonarMapBootstrapper::SolvePose(const LocalMap& frame_map,
                                                     const UncertainPose& start,
                                                     const std::vector<JuvenileScan>& z) const {
  SonarBootstrapResult out;
  const auto* sonar_map = dynamic_cast<const SonarLocalMap*>(&frame_map);
  if (sonar_map == nullptr || z.empty()) return out;
  const SonarLocalMapOptions& mo = sonar_map->Options();
  const std::vector<MapLine> lines = frame_map.Lines();
  const int nl = static_cast<int>(lines.size());
  const int nk = static_cast<int>(z.size());

  // p_k: the robot frame of reading k in the frame of the last reading, and d p_k / d u (u the
  // increments, 3 columns each; increment 0 precedes the first reading and does not enter).
  std::vector<Pose2> p(nk);
  std::vector<Eigen::MatrixXd> dp(nk, Eigen::MatrixXd::Zero(3, 3 * nk));
  Eigen::MatrixXd q = Eigen::MatrixXd::Zero(3 * nk, 3 * nk);
  for (int k = nk - 1; k > 0; --k) {
    const Pose2& u = z[k].odometry_delta;
    const Pose2 back = Inverse(u);
    p[k - 1] = Compose(p[k], back);
    dp[k - 1] = ComposeJacobianA(p[k], back) * dp[k];
    dp[k - 1].middleCols<3>(3 * k) += ComposeJacobianB(p[k]) * InverseJacobian(u);
    q.block<3, 3>(3 * k, 3 * k) = LineEkfMap::OdometryNoise(u, mo.line_map.odometry);
  }
  std::vector<Mat3> p_cov(nk);
  for (int k = 0; k < nk; ++k) p_cov[k] = dp[k] * q * dp[k].transpose();

  std::vector<UsableReturn> returns;
  for (int k = 0; k < nk; ++k) {
    for (const SonarReturn& ret : z[k].sonar.returns) {
      if (ret.transducer < 0 || ret.transducer >= static_cast<int>(mo.ring.size())) continue;
      UsableReturn u;
      u.reading = k;
      u.mount = mo.ring[ret.transducer];
      u.range = ret.range;
      if (!IsReturn(ret.range) || u.range < mo.model.min_range ||
          u.range >= mo.model.max_range_fraction * u.mount.max_range)
        continue;
      u.mount.beam_width *= mo.model.cone_scale;
      const double sigma = mo.model.range_sigma + mo.model.range_sigma_per_m * u.range;
      u.var = sigma * sigma + mo.model.model_sigma * mo.model.model_sigma;
      returns.push_back(u);
    }
  }

  const auto predict = [&](const Pose2& x, const UsableReturn& r, int l) {
    return PredictSonarRange(Compose(x, p[r.reading]), r.mount, lines[l].rho, lines[l].alpha,
                             mo.model.edge_incidence);
  };
  // The map's pairing rule (SonarLocalMap::UpdateSonar) at the estimate x with covariance c.
  const double gate = ChiSquareQuantile(mo.update.gate, 1);
  const auto associate = [&](const Pose2& x, const Mat3& c, Pairing& pairs) {
    pairs.clear();
    const Mat3 jb = ComposeJacobianB(x);
    for (int j = 0; j < static_cast<int>(returns.size()); ++j) {
      const UsableReturn& r = returns[j];
      const Mat3 ja = ComposeJacobianA(x, p[r.reading]);
      NearestLine nearest;
      for (int l = 0; l < nl; ++l) {
        const SonarRangePrediction pr = predict(x, r, l);
        if (!pr.in_cone && !(o_.edge_echoes && pr.edge_echo)) continue;
        if (!FootWithinExtent(lines[l], pr.foot, mo.update.max_extent_gap)) continue;
        const Eigen::RowVector3d hx = pr.d_pose * ja, hp = pr.d_pose * jb;
        const double s = (hx * c * hx.transpose())(0, 0) +
                         (pr.d_line * lines[l].cov * pr.d_line.transpose())(0, 0) +
                         (hp * p_cov[r.reading] * hp.transpose())(0, 0) + r.var;
        const double innov = r.range - pr.range;
        const double d2 = innov * innov / s;
        if (!(d2 < gate)) continue;
        nearest.Offer(l, d2);
      }
      if (nearest.Unambiguous(mo.update.ambiguity_margin)) pairs.emplace_back(j, nearest.best());
    }
  };
  const auto gauss_newton = [&](Pose2& x, const Pairing& pairs) {
    for (int it = 0; it < o_.max_iterations; ++it) {
      Mat3 a = Mat3::Zero();
      Vec3 g = Vec3::Zero();
      for (const auto& [j, l] : pairs) {
        const UsableReturn& r = returns[j];
        const SonarRangePrediction pr = predict(x, r, l);
        const Eigen::RowVector3d hx = pr.d_pose * ComposeJacobianA(x, p[r.reading]);
        a += hx.transpose() * hx / r.var;
        g += hx.transpose() * (r.range - pr.range) / r.var;
      }
      const Eigen::SelfAdjointEigenSolver<Mat3> eig(a);
      if (!(eig.eigenvalues()(0) > 1e-12 * eig.eigenvalues()(2))) return GaussNewton::kSingular;
      const Vec3 step = a.ldlt().solve(g);
      if (!step.allFinite()) return GaussNewton::kSingular;
      x = Pose2{x.x + step(0), x.y + step(1), WrapAngle(x.theta + step(2))};
      if (step.head<2>().norm() < 1e-6 && std::abs(step(2)) < 1e-7) return GaussNewton::kConverged;
    }
    return GaussNewton::kNotConverged;
  };
  // Cov(x) at the solution (header), J_L and the residual's chi-square over the pairs.
  const Eigen::VectorXd& state = sonar_map->Ekf().State();
  const Eigen::MatrixXd& cov = sonar_map->Ekf().Covariance();
  const auto linearise = [&](const Pose2& x, const Pairing& pairs) {
    std::vector<int> used;
    for (const auto& [j, l] : pairs)
      if (std::find(used.begin(), used.end(), l) == used.end()) used.push_back(l);
    const int m = static_cast<int>(pairs.size()), nu = static_cast<int>(used.size());
    Eigen::MatrixXd h(m, 3), h_l = Eigen::MatrixXd::Zero(m, 2 * nu),
                             h_u = Eigen::MatrixXd::Zero(m, 3 * nk);
    Eigen::VectorXd w(m);
    double d2 = 0.0;
    const Mat3 jb = ComposeJacobianB(x);
    for (int i = 0; i < m; ++i) {
      const auto [j, l] = pairs[i];
      const UsableReturn& r = returns[j];
      const SonarRangePrediction pr = predict(x, r, l);
      h.row(i) = pr.d_pose * ComposeJacobianA(x, p[r.reading]);
      const int col = static_cast<int>(std::find(used.begin(), used.end(), l) - used.begin());
      h_l.block<1, 2>(i, 2 * col) = pr.d_line;
      h_u.row(i) = pr.d_pose * jb * dp[r.reading];
      w(i) = 1.0 / r.var;
      const double e = r.range - pr.range;
      d2 += e * e / (r.var + (pr.d_line * lines[l].cov * pr.d_line.transpose())(0, 0));
    }
    const Mat3 a_inv = (h.transpose() * w.asDiagonal() * h).inverse();
    const Eigen::MatrixXd g = a_inv * h.transpose() * w.asDiagonal();
    const Eigen::MatrixXd j_u = -g * h_u;
    out.d_lines = -g * h_l;
    out.feature_index = used;
    out.observation_cov = a_inv + j_u * q * j_u.transpose();
    // P_LL of the used lines, over their canonical (rho, alpha) as Lines() reports them.
    Eigen::MatrixXd p_ll(2 * nu, 2 * nu);
    for (int a = 0; a < nu; ++a) {
      for (int b = 0; b < nu; ++b) {
        Mat2 blk = cov.block<2, 2>(3 + 2 * used[a], 3 + 2 * used[b]);
        if (state(3 + 2 * used[a]) < 0.0) blk.row(0) *= -1.0;
        if (state(3 + 2 * used[b]) < 0.0) blk.col(0) *= -1.0;
        p_ll.block<2, 2>(2 * a, 2 * b) = blk;
      }
    }
    Mat3 total = out.observation_cov + out.d_lines * p_ll * out.d_lines.transpose();
    out.pose = UncertainPose{x, 0.5 * (total + total.transpose())};
    out.paired = m;
    out.residual_d2 = d2;
  };

  Pose2 x = start.mean;
  Mat3 c = start.cov;
  Pairing pairs, solved;
  for (int round = 0; round < o_.rounds; ++round) {
    associate(x, c, pairs);
    out.rounds = round + 1;
    if (round > 0 && pairs == solved) break;  // x is the solution of this pairing
    out.paired = static_cast<int>(pairs.size());
    if (out.paired < o_.min_returns) {
      out.outcome = BootstrapOutcome::kUndetermined;
      return out;
    }
    const GaussNewton gn = gauss_newton(x, pairs);
    if (gn != GaussNewton::kConverged) {
      out.outcome = gn == GaussNewton::kSingular ? BootstrapOutcome::kUndetermined
                                                 : BootstrapOutcome::kFailed;
      return out;
    }
    solved = pairs;
    linearise(x, solved);
    c = out.pose.cov;
  }
  const Eigen::SelfAdjointEigenSolver<Mat2> pos(out.pose.cov.topLeftCorner<2, 2>());
  if (!(std::sqrt(std::max(0.0, pos.eigenvalues()(1))) <= o_.max_sigma_xy) ||
      !(std::sqrt(std::max(0.0, out.pose.cov(2, 2))) <= o_.max_sigma_theta)) {
    out.outcome = BootstrapOutcome::kUndetermined;
    return out;
  }
  const int dof = out.paired - 3;
  const Vec3 jump(x.x - start.mean.x, x.y - start.mean.y, WrapAngle(x.theta - start.mean.theta));
  const double jump_d2 = jump.dot((start.cov + out.pose.cov).ldlt().solve(jump));
  out.outcome = (dof > 0 && out.residual_d2 > ChiSquareQuantile(o_.residual_gate, dof)) ||
                        !(jump_d2 < ChiSquareQuantile(o_.residual_gate, 3))
                    ? BootstrapOutcome::kFailed
                    : BootstrapOutcome::kSolved;
  return out;
}

UncertainPose SonarMapBootstrapper::DeadReckonedSeed(const LocalMap& frame_map,
                                                     const UncertainPose& seed,
                                                     const std::vector<JuvenileScan>& z) {
  const auto* sonar_map = dynamic_cast<const SonarLocalMap*>(&frame_map);
  assert(sonar_map != nullptr);
  const OdometryNoiseOptions& odometry = sonar_map->Options().line_map.odometry;
  UncertainPose x = seed;
  for (const JuvenileScan& s : z)
    x = Compose(
        x, UncertainPose{s.odometry_delta, LineEkfMap::OdometryNoise(s.odometry_delta, odometry)});
  return x;
}

PoseBootstrap SonarMapBootstrapper::Solve(const LocalMap& map, const LocalMap& frame_map,
                                          const std::vector<JuvenileScan>& z,
                                          const UncertainPose& seed) const {
  PoseBootstrap out;
  if (dynamic_cast<const SonarLocalMap*>(&frame_map) == nullptr) return out;
  const UncertainPose start =
      o_.dead_reckoned_start ? DeadReckonedSeed(frame_map, seed, z) : map.RobotPose();
  const SonarBootstrapResult r = SolvePose(frame_map, start, z);
  out.outcome = r.outcome;
  if (r.outcome != BootstrapOutcome::kSolved) return out;
  std::unique_ptr<LocalMap> fresh = frame_map.Clone();
  auto* sonar = dynamic_cast<SonarLocalMap*>(fresh.get());
  assert(sonar != nullptr);  // a clone of a SonarLocalMap (checked above)
  sonar->SetRobotPoseFromFeatures(r.pose.mean, r.observation_cov, r.feature_index, r.d_lines);
  out.pose = sonar->RobotPose();
  out.map = std::move(fresh);
  return out;
}

}  // namespace atlas
