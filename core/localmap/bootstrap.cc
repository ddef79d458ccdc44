#include "core/localmap/bootstrap.h"

#include <Eigen/Cholesky>
#include <Eigen/LU>
#include <cmath>

#include "core/localmap/jcbb.h"

namespace atlas {
namespace {

struct Obs {
  int scan;
  int line;
  ObservedLine z;  // current robot frame, covariance includes the scan pose uncertainty
};

struct SeedJacobian {
  Mat23 h_pose;
  Mat2 h_line;
  int feature;
};

class SeedCovariance final : public JointCovariance {
 public:
  SeedCovariance(const Mat3& seed_cov, const std::vector<MapLine>& map,
                 const std::vector<SeedJacobian>& h)
      : seed_cov_(seed_cov), map_(map), h_(h) {}
  Mat2 Cross(const CandidatePair& a, const CandidatePair& b) const override {
    const SeedJacobian& ha = h_[a.tag];
    const SeedJacobian& hb = h_[b.tag];
    Mat2 c = ha.h_pose * seed_cov_ * hb.h_pose.transpose();
    if (ha.feature == hb.feature) c += ha.h_line * map_[ha.feature].cov * hb.h_line.transpose();
    return c;
  }

 private:
  const Mat3& seed_cov_;
  const std::vector<MapLine>& map_;
  const std::vector<SeedJacobian>& h_;
};

// A matched pair with the representation of the map line the observation refers to.
struct Pairing {
  const Obs* obs;
  int feature;
  bool flipped;  // the observation sees (-rho, alpha + pi)
};

// Residual z - h(x) and Jacobians for one pairing at pose x, in the pairing's representation.
Vec2 Residual(const Pose2& x, const MapLine& l, const Pairing& p, Mat23& h_pose, Mat2& h_line) {
  LinePrediction pred = PredictLine(x, l.rho, l.alpha);
  if (p.flipped) {
    pred.z(0) = -pred.z(0);
    pred.z(1) += std::numbers::pi;
    pred.d_pose.row(0) *= -1.0;
    pred.d_line.row(0) *= -1.0;
  }
  h_pose = pred.d_pose;
  h_line = pred.d_line;
  return Vec2(p.obs->z.rho - pred.z(0), WrapAngle(p.obs->z.alpha - pred.z(1)));
}

}  // namespace

BootstrapResult Bootstrap(const std::vector<MapLine>& map, const std::vector<BootstrapScan>& scans,
                          const UncertainPose& seed, const BootstrapOptions& options,
                          const AssociationOptions& association) {
  BootstrapResult result;
  result.pose = seed;
  std::vector<Obs> obs;
  for (int s = 0; s < static_cast<int>(scans.size()); ++s) {
    for (int i = 0; i < static_cast<int>(scans[s].lines.size()); ++i) {
      const ObservedLine& l = scans[s].lines[i];
      const LineTransform t = LineToParent(scans[s].pose_in_current, l.rho, l.alpha);
      ObservedLine z = ObservedLineToParent(scans[s].pose_in_current, l);
      Mat2 extra = t.d_pose * scans[s].pose_cov * t.d_pose.transpose();
      if (std::abs(WrapAngle(z.alpha - t.line(1))) > 1.0) extra(0, 1) = extra(1, 0) = -extra(0, 1);
      z.cov += extra;
      obs.push_back(Obs{s, i, z});
    }
  }

  // Correspondences proposed with the seed.
  const double gate = ChiSquareQuantile(association.individual_gate, 2);
  const double seed_spread = 3.0 * std::sqrt(std::max(0.0, seed.cov(0, 0) + seed.cov(1, 1)));
  std::vector<CandidatePair> cands;
  std::vector<SeedJacobian> jac;
  std::vector<bool> flipped;
  for (int j = 0; j < static_cast<int>(obs.size()); ++j) {
    const ObservedLine& z = obs[j].z;
    const Vec2 ea = seed.mean.TransformPoint(z.endpoint_a);
    const Vec2 eb = seed.mean.TransformPoint(z.endpoint_b);
    for (int k = 0; k < static_cast<int>(map.size()); ++k) {
      const MapLine& l = map[k];
      LinePrediction pred = PredictLine(seed.mean, l.rho, l.alpha);
      bool flip = false;
      const Vec2 nu = LineInnovation(Vec2(z.rho, z.alpha), pred, &flip);
      Mat2 s = pred.d_pose * seed.cov * pred.d_pose.transpose() +
               pred.d_line * l.cov * pred.d_line.transpose() + z.cov;
      s = 0.5 * (s + s.transpose());
      if (!(s.determinant() > 0.0)) continue;
      const double d2 = nu.dot(s.inverse() * nu);
      if (!(d2 < gate)) continue;
      const double t0 = PositionAlongLine(l.alpha, ea), t1 = PositionAlongLine(l.alpha, eb);
      const double s0 = PositionAlongLine(l.alpha, l.endpoint_a);
      const double s1 = PositionAlongLine(l.alpha, l.endpoint_b);
      const double gap =
          std::max(std::min(s0, s1) - std::max(t0, t1), std::min(t0, t1) - std::max(s0, s1));
      if (gap > association.max_extent_gap + seed_spread) continue;
      cands.push_back(CandidatePair{j, k, nu, s, d2, static_cast<int>(jac.size())});
      jac.push_back(SeedJacobian{pred.d_pose, pred.d_line, k});
      flipped.push_back(flip);
    }
  }
  JcbbOptions jo;
  jo.joint_gate = association.joint_gate;
  jo.node_budget = association.node_budget;
  jo.allow_shared_features = true;
  jo.ambiguity_margin = association.ambiguity_margin;
  const SeedCovariance cross(seed.cov, map, jac);
  const JcbbResult assoc = Jcbb(static_cast<int>(obs.size()), cands, cross, jo);
  std::vector<Pairing> pairs;
  if (assoc.status != AssociationStatus::kBudgetExhausted) {
    for (int j = 0; j < static_cast<int>(obs.size()); ++j) {
      const int c = assoc.pair_of[j];
      if (c < 0 || assoc.ambiguous[j]) continue;
      pairs.push_back(Pairing{&obs[j], cands[c].feature, flipped[c]});
      result.matches.push_back(
          BootstrapMatch{obs[j].scan, obs[j].line, cands[c].feature, map[cands[c].feature].id});
    }
  }
  const int q = static_cast<int>(pairs.size());
  if (q < options.min_matches) {
    result.status = BootstrapStatus::kTooFewMatches;
    return result;
  }
  double best_sin = 0.0;
  for (int a = 0; a < q; ++a) {
    for (int b = a + 1; b < q; ++b) {
      best_sin = std::max(
          best_sin, std::abs(std::sin(map[pairs[a].feature].alpha - map[pairs[b].feature].alpha)));
    }
  }
  if (best_sin < std::sin(options.min_angle_between)) {
    result.status = BootstrapStatus::kUnderconstrained;
    return result;
  }

  // Closed-form start, seed-free: heading from angle differences, position from the lines.
  double sum_s = 0.0, sum_c = 0.0;
  for (const Pairing& p : pairs) {
    const MapLine& l = map[p.feature];
    const double alpha_rep = l.alpha + (p.flipped ? std::numbers::pi : 0.0);
    const double th = WrapAngle(alpha_rep - p.obs->z.alpha);
    const double w = 1.0 / std::max(p.obs->z.cov(1, 1), 1e-12);
    sum_s += w * std::sin(th);
    sum_c += w * std::cos(th);
  }
  Pose2 x{0.0, 0.0, std::atan2(sum_s, sum_c)};
  Mat2 a = Mat2::Zero();
  Vec2 bvec = Vec2::Zero();
  for (const Pairing& p : pairs) {
    const MapLine& l = map[p.feature];
    const double sign = p.flipped ? -1.0 : 1.0;
    const Vec2 nrm(sign * std::cos(l.alpha), sign * std::sin(l.alpha));
    const double w = 1.0 / std::max(p.obs->z.cov(0, 0), 1e-12);
    a += w * nrm * nrm.transpose();
    bvec += w * nrm * (sign * l.rho - p.obs->z.rho);
  }
  const Vec2 xy = a.ldlt().solve(bvec);
  x.x = xy(0);
  x.y = xy(1);

  Mat3 info = Mat3::Identity();
  for (int it = 0; it < options.iterations; ++it) {
    info.setZero();
    Vec3 g = Vec3::Zero();
    for (const Pairing& p : pairs) {
      Mat23 hp;
      Mat2 hl;
      const Vec2 r = Residual(x, map[p.feature], p, hp, hl);
      const Mat2 w = p.obs->z.cov.inverse();
      info += hp.transpose() * w * hp;
      g += hp.transpose() * w * r;
    }
    const Vec3 dx = info.ldlt().solve(g);
    x = Pose2{x.x + dx(0), x.y + dx(1), WrapAngle(x.theta + dx(2))};
    if (dx.norm() < 1e-10) break;
  }
  info.setZero();
  std::vector<Mat23> hps(q);
  std::vector<Mat2> hls(q);
  double d2 = 0.0;
  for (int i = 0; i < q; ++i) {
    const Pairing& p = pairs[i];
    const Vec2 r = Residual(x, map[p.feature], p, hps[i], hls[i]);
    info += hps[i].transpose() * p.obs->z.cov.inverse() * hps[i];
    const Mat2 s = p.obs->z.cov + hls[i] * map[p.feature].cov * hls[i].transpose();
    d2 += r.dot(s.inverse() * r);
  }
  const Mat3 info_inv = info.inverse();
  result.residual_d2 = d2;
  result.residual_dof = 2 * q - 3;
  result.observation_cov = info_inv;
  // d pose / d line for every distinct matched feature.
  for (const Pairing& p : pairs) {
    bool seen = false;
    for (int f : result.feature_index) seen = seen || f == p.feature;
    if (!seen) result.feature_index.push_back(p.feature);
  }
  result.d_lines.setZero(3, 2 * static_cast<int>(result.feature_index.size()));
  for (int i = 0; i < q; ++i) {
    int slot = 0;
    while (result.feature_index[slot] != pairs[i].feature) ++slot;
    result.d_lines.middleCols<2>(2 * slot) -=
        info_inv * hps[i].transpose() * pairs[i].obs->z.cov.inverse() * hls[i];
  }
  Mat3 cov = info_inv;
  for (size_t f = 0; f < result.feature_index.size(); ++f) {
    const auto jf = result.d_lines.middleCols<2>(2 * f);
    cov += jf * map[result.feature_index[f]].cov * jf.transpose();
  }
  result.pose = UncertainPose{x, 0.5 * (cov + cov.transpose())};
  if (result.residual_dof > 0 &&
      d2 > ChiSquareQuantile(options.residual_gate, result.residual_dof)) {
    result.status = BootstrapStatus::kInconsistent;
    return result;
  }
  result.status = BootstrapStatus::kSolved;
  return result;
}

}  // namespace atlas
