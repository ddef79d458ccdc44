#include "core/sonar/sonar_line_initializer.h"

#include <Eigen/Cholesky>
#include <Eigen/LU>
#include <algorithm>
#include <cmath>

#include "core/sonar/sonar_geometry.h"

namespace atlas {
namespace {

bool DifferentLines(const Vec2& a, const Vec2& b, const SonarInitOptions& o) {
  return std::abs(WrapAngle(a(1) - b(1))) > o.rival_alpha || std::abs(a(0) - b(0)) > o.rival_rho;
}

}  // namespace

SonarLineInitializer::SonarLineInitializer(const SonarInitOptions& init,
                                           const SonarModelOptions& model)
    : o_(init), m_(model), rng_(init.seed) {
  if (!o_.edge_echoes) m_.edge_incidence = 0.0;
  vantage_.reserve(o_.max_vantage + 1);
  returns_.reserve(o_.max_returns + 1);
}

void SonarLineInitializer::Clear() {
  vantage_.clear();
  returns_.clear();
  moved_since_vantage_ = true;
}

void SonarLineInitializer::Predict(const Pose2& u, const Mat3& q) {
  if (u.x == 0.0 && u.y == 0.0 && u.theta == 0.0) return;
  moved_since_vantage_ = true;
  const Pose2 w = Inverse(u);
  const Mat3 jinv = InverseJacobian(u);
  const Mat3 qw = jinv * q * jinv.transpose();
  const Mat3 j2 = ComposeJacobianB(w);
  for (SonarVantage& v : vantage_) {
    const Mat3 j1 = ComposeJacobianA(w, v.pose);
    v.pose = Compose(w, v.pose);
    v.cov = j1 * qw * j1.transpose() + j2 * v.cov * j2.transpose();
  }
  DropOld();
}

void SonarLineInitializer::DropOld() {
  int first = 0;
  const int nv = static_cast<int>(vantage_.size());
  while (first < nv && (nv - first > o_.max_vantage ||
                        std::hypot(vantage_[first].pose.x, vantage_[first].pose.y) > o_.window_m)) {
    ++first;
  }
  int first_return = 0;
  const int nr = static_cast<int>(returns_.size());
  while (first_return < nr &&
         (returns_[first_return].vantage < first || nr - first_return > o_.max_returns)) {
    ++first_return;
  }
  if (first == 0 && first_return == 0) return;
  vantage_.erase(vantage_.begin(), vantage_.begin() + first);
  returns_.erase(returns_.begin(), returns_.begin() + first_return);
  for (BufferedReturn& r : returns_) r.vantage -= first;
  // Vantage points without returns left at the front are dropped on the next call.
}

void SonarLineInitializer::Add(const SonarTransducer& mount, double range) {
  if (moved_since_vantage_ || vantage_.empty()) {
    vantage_.push_back(SonarVantage{});
    vantage_.back().id = next_vantage_id_++;
    moved_since_vantage_ = false;
  }
  BufferedReturn r;
  r.vantage = static_cast<int>(vantage_.size()) - 1;
  r.mount = mount;
  r.mount.beam_width *= m_.cone_scale;
  r.range = range;
  returns_.push_back(r);
  DropOld();
}

std::vector<int64_t> SonarLineInitializer::VantagesInUse() const {
  std::vector<int64_t> ids;
  for (const BufferedReturn& r : returns_) {
    const int64_t id = vantage_[r.vantage].id;
    if (ids.empty() || ids.back() != id) ids.push_back(id);
  }
  return ids;
}

double SonarLineInitializer::ReturnVariance(const BufferedReturn& r, double rho,
                                            double alpha) const {
  const SonarRangePrediction p =
      PredictSonarRange(vantage_[r.vantage].pose, r.mount, rho, alpha, m_.edge_incidence);
  return RangeVariance(r, p.d_pose);
}

double SonarLineInitializer::RangeVariance(const BufferedReturn& r,
                                           const Eigen::RowVector3d& d_vantage) const {
  const double sigma = m_.range_sigma + m_.range_sigma_per_m * r.range;
  return sigma * sigma + m_.model_sigma * m_.model_sigma +
         (d_vantage * vantage_[r.vantage].cov * d_vantage.transpose())(0, 0);
}

int SonarLineInitializer::CountInliers(const Vec2& line, std::vector<char>& mask) const {
  const int n = static_cast<int>(returns_.size());
  mask.assign(n, 0);
  int count = 0;
  const double k2 = o_.inlier_sigmas * o_.inlier_sigmas;
  for (int j = 0; j < n; ++j) {
    const BufferedReturn& r = returns_[j];
    const SonarRangePrediction p =
        PredictSonarRange(vantage_[r.vantage].pose, r.mount, line(0), line(1), m_.edge_incidence);
    if (!p.echoes()) continue;
    const double e = r.range - p.range;
    if (e * e > k2 * ReturnVariance(r, line(0), line(1))) continue;
    mask[j] = 1;
    ++count;
  }
  return count;
}

bool SonarLineInitializer::Refine(Vec2& line, const std::vector<char>& mask, Mat2& cov) const {
  for (int it = 0; it < 4; ++it) {
    Mat2 a = Mat2::Zero();
    Vec2 b = Vec2::Zero();
    for (size_t j = 0; j < returns_.size(); ++j) {
      if (!mask[j]) continue;
      const BufferedReturn& r = returns_[j];
      const SonarRangePrediction p =
          PredictSonarRange(vantage_[r.vantage].pose, r.mount, line(0), line(1), m_.edge_incidence);
      const double w = 1.0 / ReturnVariance(r, line(0), line(1));
      a += w * p.d_line.transpose() * p.d_line;
      b += w * p.d_line.transpose() * (r.range - p.range);
    }
    if (!(std::abs(a.determinant()) > 1e-12)) return false;
    const Vec2 step = a.ldlt().solve(b);
    line += step;
    CanonicalizeLine(line(0), line(1));
    cov = a.inverse();
    if (step.norm() < 1e-7) break;
  }
  cov(0, 0) += o_.min_rho_sigma * o_.min_rho_sigma;
  cov(1, 1) += o_.min_alpha_sigma * o_.min_alpha_sigma;
  return std::isfinite(line(0)) && std::isfinite(line(1));
}

int SonarLineInitializer::PointSupport(const std::vector<char>& mask, Vec2 point) const {
  const double k2 = o_.inlier_sigmas * o_.inlier_sigmas;
  std::vector<char> use = mask;
  int count = 0;
  for (int round = 0; round < 2; ++round) {
    for (int it = 0; it < 8; ++it) {
      Mat2 a = Mat2::Zero();
      Vec2 b = Vec2::Zero();
      for (size_t j = 0; j < returns_.size(); ++j) {
        if (!use[j]) continue;
        const BufferedReturn& r = returns_[j];
        const Pose2 s = Compose(vantage_[r.vantage].pose, r.mount.pose);
        const Vec2 d = point - Vec2(s.x, s.y);
        const double range = d.norm();
        if (!(range > 1e-6)) continue;
        const Eigen::RowVector2d jac = d.transpose() / range;
        a += jac.transpose() * jac;
        b += jac.transpose() * (r.range - range);
      }
      if (!(std::abs(a.determinant()) > 1e-12)) return 0;
      const Vec2 step = a.ldlt().solve(b);
      point += step;
      if (!std::isfinite(point(0)) || !std::isfinite(point(1))) return 0;
      if (step.norm() < 1e-6) break;
    }
    count = 0;
    for (size_t j = 0; j < returns_.size(); ++j) {
      if (!mask[j]) continue;
      use[j] = 0;
      const BufferedReturn& r = returns_[j];
      const SonarVantage& v = vantage_[r.vantage];
      const Pose2 s = Compose(v.pose, r.mount.pose);
      const Vec2 d = point - Vec2(s.x, s.y);
      const double range = d.norm();
      if (!(range > 1e-6)) continue;
      if (std::abs(WrapAngle(std::atan2(d.y(), d.x()) - s.theta)) > 0.5 * r.mount.beam_width) {
        continue;
      }
      // d range / d vantage: the range's gradient in the sensor position (-d / range) through
      // the sensor position's Jacobian in the vantage pose.
      const Eigen::RowVector3d d_vantage =
          (-d / range).transpose() * ComposeJacobianA(v.pose, r.mount.pose).topRows<2>();
      const double e = r.range - range;
      if (e * e > k2 * RangeVariance(r, d_vantage)) continue;
      use[j] = 1;
      ++count;
    }
    if (count < 3) break;
  }
  return count;
}

GroupingDecision SonarLineInitializer::Decide() {
  GroupingDecision out;
  struct Hypothesis {
    Vec2 line;
    int support = 0;
    std::vector<char> mask;
  };
  for (int round = 0; round < o_.max_new_per_decision; ++round) {
    const int n = static_cast<int>(returns_.size());
    if (n < o_.min_support) return out;
    std::vector<Hypothesis> hyps;
    std::uniform_int_distribution<int> pick(0, n - 1);
    for (int it = 0; it < o_.iterations; ++it) {
      const BufferedReturn& a = returns_[pick(rng_)];
      const BufferedReturn& b = returns_[pick(rng_)];
      const Pose2& va = vantage_[a.vantage].pose;
      const Pose2& vb = vantage_[b.vantage].pose;
      if (std::hypot(va.x - vb.x, va.y - vb.y) < o_.min_pair_baseline) continue;
      Vec2 lines[2];
      const int count =
          CommonTangentLines(Compose(va, a.mount.pose), a.range, 0.5 * a.mount.beam_width,
                             Compose(vb, b.mount.pose), b.range, 0.5 * b.mount.beam_width, lines);
      for (int c = 0; c < count; ++c) {
        Hypothesis h;
        h.line = lines[c];
        h.support = CountInliers(h.line, h.mask);
        ++out.hypotheses;
        if (h.support >= 2) hyps.push_back(std::move(h));
      }
    }
    if (hyps.empty()) return out;
    const auto best_it = std::max_element(
        hyps.begin(), hyps.end(),
        [](const Hypothesis& x, const Hypothesis& y) { return x.support < y.support; });
    Hypothesis best = *best_it;
    if (best.support < o_.min_support) return out;
    Mat2 cov;
    if (!Refine(best.line, best.mask, cov)) return out;
    best.support = CountInliers(best.line, best.mask);
    if (best.support < o_.min_support || !Refine(best.line, best.mask, cov)) return out;
    // Support from enough distinct vantage points over enough baseline.
    std::vector<int> vs;
    for (int j = 0; j < n; ++j) {
      if (best.mask[j]) vs.push_back(returns_[j].vantage);
    }
    std::sort(vs.begin(), vs.end());
    vs.erase(std::unique(vs.begin(), vs.end()), vs.end());
    double baseline = 0.0;
    for (size_t i = 0; i < vs.size(); ++i) {
      for (size_t k = i + 1; k < vs.size(); ++k) {
        const Pose2& p = vantage_[vs[i]].pose;
        const Pose2& q = vantage_[vs[k]].pose;
        baseline = std::max(baseline, std::hypot(p.x - q.x, p.y - q.y));
      }
    }
    if (static_cast<int>(vs.size()) < o_.min_vantage || baseline < o_.min_baseline) return out;
    // Delayed decision: a rival interpretation of the same returns makes it ambiguous.
    for (const Hypothesis& h : hyps) {
      if (!DifferentLines(h.line, best.line, o_)) continue;
      int shared = 0;
      for (int j = 0; j < n; ++j) shared += (h.mask[j] && best.mask[j]) ? 1 : 0;
      if (shared >= o_.rival_overlap * best.support && h.support >= o_.rival_ratio * best.support) {
        out.outcome = GroupingOutcome::kAmbiguous;
        return out;
      }
    }
    InitialisedLine init;
    init.line.rho = best.line(0);
    init.line.alpha = best.line(1);
    init.line.cov = cov;
    init.support = best.support;
    init.baseline = baseline;
    double lo = 1e300, hi = -1e300;
    for (int j = 0; j < n; ++j) {
      if (!best.mask[j]) continue;
      const BufferedReturn& r = returns_[j];
      const SonarRangePrediction p = PredictSonarRange(
          vantage_[r.vantage].pose, r.mount, best.line(0), best.line(1), m_.edge_incidence);
      init.tangent_points.push_back(p.foot);
      init.vantage.push_back(vantage_[r.vantage].pose);
      init.sensors.push_back(Compose(vantage_[r.vantage].pose, r.mount.pose));
      init.ranges.push_back(r.range);
      init.mounts.push_back(r.mount);
      init.vantage_ids.push_back(vantage_[r.vantage].id);
      const double t = PositionAlongLine(best.line(1), p.foot);
      lo = std::min(lo, t);
      hi = std::max(hi, t);
    }
    if (hi - lo < o_.min_extent_ratio * baseline) return out;  // point-like reflector
    if (o_.point_rival) {
      Vec2 centre = Vec2::Zero();
      for (const Vec2& f : init.tangent_points) centre += f;
      centre /= static_cast<double>(init.tangent_points.size());
      if (PointSupport(best.mask, centre) >= o_.rival_ratio * best.support) return out;
    }
    init.line.endpoint_a = PointOnLine(best.line(0), best.line(1), lo);
    init.line.endpoint_b = PointOnLine(best.line(0), best.line(1), hi);
    init.line.num_points = best.support;
    out.lines.push_back(std::move(init));
    out.outcome = GroupingOutcome::kAccepted;
    std::vector<BufferedReturn> kept;
    kept.reserve(returns_.size());
    for (int j = 0; j < n; ++j) {
      if (!best.mask[j]) kept.push_back(returns_[j]);
    }
    returns_.swap(kept);
  }
  return out;
}

}  // namespace atlas
