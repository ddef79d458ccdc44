#include "core/sonar/sonar_local_map.h"

#include <Eigen/Cholesky>
#include <Eigen/LU>
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstring>

#include "core/localmap/jcbb.h"
#include "core/sonar/sonar_geometry.h"

namespace atlas {
namespace {

constexpr uint32_t kMagic = 0x4e535441;  // "ATSN"
constexpr uint32_t kVersion = 1;

// A line initialised from buffered returns, refitted in the map frame over the delayed vantage
// states (DelayedVantages): the returns' ranges r_j = h(v_j, L) + noise are fitted by Gauss-
// Newton with the range variances alone, and the vantage poses' errors enter through
// dL = -B dv, B = A^-1 sum_j w_j h_L,j^T h_v,j (A = sum_j w_j h_L,j^T h_L,j), so that
//   Cov(L) = A^-1 + B V B^T (+ floors),  Cov(L, s) = -B C,  Cov(L, v) = -B V.
struct JointLine {
  Vec2 line = Vec2::Zero();
  Mat2 cov = Mat2::Zero();
  Eigen::MatrixXd cross;  // 2 x n, with the EKF state
  Eigen::MatrixXd cov_v;  // 3m x 2, with the vantage points
  Vec2 a = Vec2::Zero(), b = Vec2::Zero();
};

bool FitJointLine(const InitialisedLine& init, const DelayedVantages& dv, const Pose2& robot,
                  const SonarModelOptions& m, const SonarInitOptions& io, JointLine& out) {
  const int count = static_cast<int>(init.ranges.size());
  std::vector<int> index(count);
  for (int j = 0; j < count; ++j) {
    index[j] = dv.IndexOf(init.vantage_ids[j]);
    if (index[j] < 0) return false;
  }
  Vec2 line = LineToParent(robot, init.line.rho, init.line.alpha).line;
  CanonicalizeLine(line(0), line(1));
  Mat2 a;
  Eigen::MatrixXd hv = Eigen::MatrixXd::Zero(2, 3 * dv.Size());  // sum_j w_j h_L^T h_v
  for (int it = 0; it < 5; ++it) {
    a.setZero();
    hv.setZero();
    Vec2 g = Vec2::Zero();
    for (int j = 0; j < count; ++j) {
      const SonarRangePrediction p =
          PredictSonarRange(dv.Pose(index[j]), init.mounts[j], line(0), line(1), m.edge_incidence);
      if (!p.echoes()) continue;
      const double sigma = m.range_sigma + m.range_sigma_per_m * init.ranges[j];
      const double w = 1.0 / (sigma * sigma + m.model_sigma * m.model_sigma);
      a += w * p.d_line.transpose() * p.d_line;
      g += w * p.d_line.transpose() * (init.ranges[j] - p.range);
      hv.block<2, 3>(0, 3 * index[j]) += w * p.d_line.transpose() * p.d_pose;
    }
    if (!(std::abs(a.determinant()) > 1e-12)) return false;
    const Vec2 step = a.ldlt().solve(g);
    if (it == 4 || step.norm() < 1e-9) break;
    line += step;
    CanonicalizeLine(line(0), line(1));
  }
  if (!std::isfinite(line(0)) || !std::isfinite(line(1))) return false;
  const Mat2 a_inv = a.inverse();
  const Eigen::MatrixXd bm = a_inv * hv;  // B, 2 x 3m
  const Eigen::MatrixXd bv = bm * dv.Covariance();
  out.line = line;
  out.cov = a_inv + bv * bm.transpose();
  out.cov(0, 0) += io.min_rho_sigma * io.min_rho_sigma;
  out.cov(1, 1) += io.min_alpha_sigma * io.min_alpha_sigma;
  out.cov = 0.5 * (out.cov + out.cov.transpose()).eval();
  out.cross = -bm * dv.CrossCovariance();
  out.cov_v = -bv.transpose();
  for (const auto& [from, to] :
       {std::pair{&init.line.endpoint_a, &out.a}, std::pair{&init.line.endpoint_b, &out.b}}) {
    *to = PointOnLine(line(0), line(1), PositionAlongLine(line(1), robot.TransformPoint(*from)));
  }
  return true;
}

// The point an edge-of-cone echo paired with `line` (map frame) grows its extent to: the point of
// the cone's footprint on the line nearest to the extent (none when they overlap). An edge echo's
// foot (where the edge ray meets the line) is where a wall would be if one were there; for the
// jamb of an alcove seen from the corridor the echo comes from its corner, and that point on the
// jamb's line lies in the corridor (atlas-sonar-eval atlas --world alcoves: robot NEES 34.6 ->
// 8.7 over 10 runs; growing every pairing this way made 5 false closures instead of 1). In-cone
// echoes grow the extent to their tangent point.
Vec2 ExtentGrowth(const Pose2& sensor, double half, const MapLine& line, const Vec2& foot) {
  double lo = 0.0, hi = 0.0;
  if (!ConeFootprint(sensor, half, line.rho, line.alpha, lo, hi)) return foot;
  const double ta = PositionAlongLine(line.alpha, line.endpoint_a);
  const double tb = PositionAlongLine(line.alpha, line.endpoint_b);
  if (hi < std::min(ta, tb)) return PointOnLine(line.rho, line.alpha, hi);
  if (lo > std::max(ta, tb)) return PointOnLine(line.rho, line.alpha, lo);
  return line.endpoint_a;  // the footprint overlaps the extent
}

}  // namespace

SonarLocalMap::SonarLocalMap(const SonarLocalMapOptions& options)
    : o_(options),
      ekf_(options.line_map),
      init_(options.init, options.model),
      sonar_recent_(options.line_map.quality.window) {}

std::unique_ptr<LocalMap> SonarLocalMap::Clone() const {
  return std::make_unique<SonarLocalMap>(*this);
}

void SonarLocalMap::Predict(const Pose2& u) { PredictWith(u, nullptr); }

void SonarLocalMap::Predict(const Pose2& u, const Mat3& covariance) { PredictWith(u, &covariance); }

void SonarLocalMap::PredictWith(const Pose2& u, const Mat3* covariance) {
  const Pose2 before = ekf_.RobotPose().mean;
  if (covariance != nullptr) {
    ekf_.Predict(u, *covariance);
  } else {
    ekf_.Predict(u);
  }
  if (o_.sensors != RangeSensors::kLaser) {
    vantages_.Predict(ComposeJacobianA(before, u));
    init_.Predict(u, covariance != nullptr ? *covariance
                                           : LineEkfMap::OdometryNoise(u, o_.line_map.odometry));
    SyncVantages();
  }
}

template <typename Laser>
ScanUpdate SonarLocalMap::UpdateWithLaser(const Laser& laser, bool allow_new_features) {
  if (o_.sensors == RangeSensors::kSonar) return ScanUpdate{};
  if (vantages_.Size() == 0) return ekf_.Update(laser, allow_new_features);
  const Eigen::VectorXd x0 = ekf_.State();
  const Eigen::MatrixXd p0 = ekf_.Covariance();
  const ScanUpdate out = ekf_.Update(laser, allow_new_features);
  vantages_.Follow(x0, p0, ekf_.State(), ekf_.Covariance());
  return out;
}

ScanUpdate SonarLocalMap::Update(const LaserScan& scan, bool allow_new_features) {
  return UpdateWithLaser(scan, allow_new_features);
}

ScanUpdate SonarLocalMap::Update(const ScanObservation& observation, bool allow_new_features) {
  return UpdateWithLaser(observation, allow_new_features);
}

void SonarLocalMap::ResetRobotPose(const UncertainPose& pose) {
  const Pose2 before = ekf_.RobotPose().mean;
  const Eigen::MatrixXd p0 = ekf_.Covariance();
  ekf_.ResetRobotPose(pose);
  vantages_.Reanchor(before, p0, ekf_.RobotPose().mean, ekf_.RobotPose().cov);
}

void SonarLocalMap::SetRobotPoseFromFeatures(
    const Pose2& pose, const Mat3& observation_cov, const std::vector<int>& feature_index,
    const Eigen::Matrix<double, 3, Eigen::Dynamic>& d_lines) {
  init_.Clear();
  vantages_.Clear();
  ekf_.SetRobotPoseFromFeatures(pose, observation_cov, feature_index, d_lines);
}

void SonarLocalMap::SyncVantages() {
  if (!o_.init.delayed_states) return;
  const std::vector<int64_t> in_use = init_.VantagesInUse();
  vantages_.Keep(in_use);
  for (const int64_t id : in_use) {
    if (vantages_.IndexOf(id) < 0) vantages_.Augment(id, ekf_.State(), ekf_.Covariance());
  }
}

void SonarLocalMap::RefreshVantages() {
  if (!o_.init.delayed_states) return;
  const Pose2 robot = ekf_.RobotPose().mean;
  const std::vector<SonarVantage>& v = init_.Vantages();
  for (int i = 0; i < static_cast<int>(v.size()); ++i) {
    const int k = vantages_.IndexOf(v[i].id);
    if (k < 0) continue;
    Pose2 pose;
    Mat3 cov;
    vantages_.Relative(k, robot, ekf_.Covariance(), pose, cov);
    init_.SetVantage(i, pose, cov);
  }
}

bool SonarLocalMap::Duplicate(const ObservedLine& z) const {
  const double loose = ChiSquareQuantile(o_.update.loose_gate, 2);
  const Pose2 robot = ekf_.RobotPose().mean;
  const Eigen::VectorXd& x = ekf_.State();
  const Eigen::MatrixXd& p = ekf_.Covariance();
  const ObservedLine in_map = ObservedLineToParent(robot, z);
  for (const MapLine& l : ekf_.Lines()) {
    if (std::abs(WrapAngle(l.alpha - in_map.alpha)) < o_.update.duplicate_alpha &&
        std::abs(l.rho - in_map.rho) < o_.update.duplicate_rho) {
      return true;
    }
  }
  for (int k = 0; k < ekf_.Complexity(); ++k) {
    const int ik = 3 + 2 * k;
    LinePrediction pred = PredictLine(robot, x(ik), x(ik + 1));
    const Vec2 nu = LineInnovation(Vec2(z.rho, z.alpha), pred);
    Eigen::Matrix<double, 2, 5> h;
    h << pred.d_pose, pred.d_line;
    Eigen::Matrix<double, 5, 5> pk;
    pk << p.topLeftCorner<3, 3>(), p.block<3, 2>(0, ik), p.block<2, 3>(ik, 0),
        p.block<2, 2>(ik, ik);
    const Mat2 s = h * pk * h.transpose() + z.cov;
    if (nu.dot(s.ldlt().solve(nu)) < loose) return true;
  }
  return false;
}

bool SonarLocalMap::ThroughWall(const Pose2& sensor, double half_cone, double range) const {
  const double sigma = o_.model.range_sigma + o_.model.range_sigma_per_m * range;
  const double limit = range - o_.update.behind_sigmas * sigma;
  if (!(limit > 0.0)) return false;
  const Vec2 origin(sensor.x, sensor.y);
  for (const MapLine& l : ekf_.Lines()) {
    const Vec2 ab = l.endpoint_b - l.endpoint_a;
    bool blocked = true;
    for (const double off : {-half_cone, 0.0, half_cone}) {
      const Vec2 u(std::cos(sensor.theta + off), std::sin(sensor.theta + off));
      // origin + t u = a + s ab, t in (0, limit), s in [0, 1].
      const double det = ab.x() * u.y() - ab.y() * u.x();
      if (std::abs(det) < 1e-9) {
        blocked = false;
        break;
      }
      const Vec2 w = l.endpoint_a - origin;
      const double t = (ab.x() * w.y() - ab.y() * w.x()) / det;
      const double sp = (u.x() * w.y() - u.y() * w.x()) / det;
      if (!(t > 0.0 && t < limit && sp >= 0.0 && sp <= 1.0)) {
        blocked = false;
        break;
      }
    }
    if (blocked) return true;
  }
  return false;
}

bool FootWithinExtent(const MapLine& line, const Vec2& foot, double max_extent_gap) {
  const double t = PositionAlongLine(line.alpha, foot);
  const double ta = PositionAlongLine(line.alpha, line.endpoint_a);
  const double tb = PositionAlongLine(line.alpha, line.endpoint_b);
  return t >= std::min(ta, tb) - max_extent_gap && t <= std::max(ta, tb) + max_extent_gap;
}

bool NearestLine::Offer(int k, double d2) {
  if (best_ < 0 || d2 < best_d2_) {
    if (best_ >= 0) second_d2_ = best_d2_;
    best_ = k;
    best_d2_ = d2;
    return true;
  }
  if (second_d2_ < 0.0 || d2 < second_d2_) second_d2_ = d2;
  return false;
}

SonarUpdate SonarLocalMap::UpdateSonar(const SonarReading& reading,
                                       const std::vector<SonarTransducer>& ring,
                                       bool allow_new_features) {
  SonarUpdate out;
  out.returns = static_cast<int>(reading.returns.size());
  if (o_.sensors == RangeSensors::kLaser) return out;
  const double gate = ChiSquareQuantile(o_.update.gate, 1);
  const double loose = ChiSquareQuantile(o_.update.loose_gate, 1);
  const Pose2 robot = ekf_.RobotPose().mean;
  const Eigen::VectorXd& x = ekf_.State();
  const Eigen::MatrixXd& p = ekf_.Covariance();
  const int n = static_cast<int>(x.size());
  const int nf = ekf_.Complexity();
  const std::vector<MapLine> lines = ekf_.Lines();

  const int max_rows = out.returns;
  Eigen::VectorXd nu(max_rows);
  Eigen::MatrixXd h = Eigen::MatrixXd::Zero(max_rows, n);
  Eigen::VectorXd r(max_rows);
  std::vector<std::pair<int, Vec2>> extents;  // feature index, tangent point
  std::vector<SonarPairing> pairings;
  std::vector<std::pair<SonarTransducer, double>> unexplained;
  int rows = 0;
  Eigen::RowVectorXd hk(n);
  for (int ri = 0; ri < out.returns; ++ri) {
    const SonarReturn& ret = reading.returns[ri];
    if (ret.transducer < 0 || ret.transducer >= static_cast<int>(ring.size())) continue;
    SonarTransducer mount = ring[ret.transducer];
    const double range = ret.range;
    if (!IsReturn(ret.range) || range < o_.model.min_range ||
        range >= o_.model.max_range_fraction * mount.max_range) {
      continue;
    }
    ++out.usable;
    mount.beam_width *= o_.model.cone_scale;
    const double sigma = o_.model.range_sigma + o_.model.range_sigma_per_m * range;
    const double var = sigma * sigma + o_.model.model_sigma * o_.model.model_sigma;
    NearestLine nearest;
    double best_nu = 0.0;
    Eigen::RowVectorXd best_h(n);
    Vec2 best_foot = Vec2::Zero();
    bool best_edge = false;
    bool near = false, behind = false;
    for (int k = 0; k < nf; ++k) {
      const int ik = 3 + 2 * k;
      const SonarRangePrediction pr =
          PredictSonarRange(robot, mount, x(ik), x(ik + 1), o_.model.edge_incidence);
      if (!pr.echoes()) continue;
      if (!FootWithinExtent(lines[k], pr.foot, o_.update.max_extent_gap)) continue;
      hk.setZero();
      hk.head<3>() = pr.d_pose;
      hk.segment<2>(ik) = pr.d_line;
      const double s = (hk * p * hk.transpose())(0, 0) + var;
      const double innov = range - pr.range;
      const double d2 = innov * innov / s;
      if (d2 < loose) near = true;
      if (innov > o_.update.behind_sigmas * std::sqrt(s)) behind = true;
      if (!(d2 < gate)) continue;
      if (nearest.Offer(k, d2)) {
        best_nu = innov;
        best_h = hk;
        best_foot = pr.foot;
        best_edge = pr.edge_echo;
      }
    }
    const int best = nearest.best();
    if (nearest.Unambiguous(o_.update.ambiguity_margin)) {
      nu(rows) = best_nu;
      h.row(rows) = best_h;
      r(rows) = var;
      ++rows;
      extents.emplace_back(best, best_edge && o_.update.edge_extent_footprint
                                     ? ExtentGrowth(Compose(robot, mount.pose),
                                                    0.5 * mount.beam_width, lines[best], best_foot)
                                     : best_foot);
      pairings.push_back(SonarPairing{ri, best, best_edge, best_nu});
    } else if (best >= 0) {
      ++out.ambiguous;
    } else if (!near &&
               (behind || ThroughWall(Compose(robot, mount.pose), 0.5 * mount.beam_width, range))) {
      ++out.behind;
    } else if (!near) {
      unexplained.emplace_back(ring[ret.transducer], range);
    }
  }
  if (rows > 0) {
    const Eigen::MatrixXd rm = r.head(rows).asDiagonal();
    const Eigen::MatrixXd p0 = vantages_.Size() > 0 ? ekf_.Covariance() : Eigen::MatrixXd();
    if (ekf_.UpdateWithMeasurements(nu.head(rows), h.topRows(rows), rm)) {
      vantages_.Update(nu.head(rows), h.topRows(rows), rm, p0);
      out.matched = rows;
      out.pairings = std::move(pairings);
      for (const auto& [k, foot] : extents) ekf_.GrowFeatureExtent(k, foot, foot);
    }
  }
  for (const auto& [mount, range] : unexplained) init_.Add(mount, range);
  out.buffered = static_cast<int>(unexplained.size());
  SyncVantages();
  if (allow_new_features && ekf_.Complexity() < ekf_.Capacity()) {
    RefreshVantages();
    GroupingDecision d = init_.Decide();
    out.grouping = d.outcome;
    for (InitialisedLine& line : d.lines) {
      if (ekf_.Complexity() >= ekf_.Capacity() || Duplicate(line.line)) continue;
      int id = -1;
      if (!o_.init.delayed_states) {
        id = ekf_.AddObservedFeature(line.line);
      } else {
        JointLine joint;
        if (!FitJointLine(line, vantages_, ekf_.RobotPose().mean, init_.Model(), o_.init, joint)) {
          continue;
        }
        id = ekf_.AddJointFeature(joint.line, joint.cov, joint.cross, joint.a, joint.b);
        if (id >= 0) vantages_.AppendFeature(joint.cov_v);
      }
      if (id >= 0) {
        ++out.added;
        out.initialised.push_back(std::move(line));
      }
    }
    if (out.added > 0) {
      const Pose2 now = ekf_.RobotPose().mean;
      init_.DropReturnsIf([&](const Pose2& sensor, const SonarTransducer& m, double range) {
        return ThroughWall(Compose(now, sensor), 0.5 * m.beam_width, range);
      });
    }
    SyncVantages();
  }
  sonar_recent_.Add(out.usable, out.matched);
  return out;
}

ScanUpdate SonarLocalMap::UpdateWithSonar(const SonarReading& reading, bool allow_new_features) {
  const SonarUpdate s = UpdateSonar(reading, o_.ring, allow_new_features);
  ScanUpdate out;
  out.observations = s.usable;
  out.matched = s.matched;
  out.added = s.added;
  out.ambiguous = s.ambiguous > 0;
  return out;
}

double SonarLocalMap::Quality() const {
  const Mat3 cov = ekf_.RobotPose().cov;
  switch (o_.sensors) {
    case RangeSensors::kLaser:
      return ekf_.Quality();
    case RangeSensors::kSonar:
      return QualityMetric(cov, sonar_recent_.Matched(), sonar_recent_.Observations(),
                           o_.line_map.quality);
    case RangeSensors::kBoth:
      return QualityMetric(cov, sonar_recent_.Matched() + ekf_.Recent().Matched(),
                           sonar_recent_.Observations() + ekf_.Recent().Observations(),
                           o_.line_map.quality);
  }
  return 0.0;
}

std::string SonarLocalMap::Serialize() const {
  std::string out(8, '\0');
  std::memcpy(out.data(), &kMagic, 4);
  std::memcpy(out.data() + 4, &kVersion, 4);
  return out + ekf_.Serialize();
}

bool SonarLocalMap::Deserialize(const std::string& bytes) {
  if (bytes.size() < 8) return false;
  uint32_t magic = 0, version = 0;
  std::memcpy(&magic, bytes.data(), 4);
  std::memcpy(&version, bytes.data() + 4, 4);
  if (magic != kMagic || version != kVersion) return false;
  if (!ekf_.Deserialize(bytes.substr(8))) return false;
  init_.Clear();
  vantages_.Clear();
  sonar_recent_.Clear();
  return true;
}

}  // namespace atlas
