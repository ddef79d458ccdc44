#include "core/sonar/sonar_local_map.h"

#include <Eigen/Cholesky>
#include <cmath>
#include <cstdint>
#include <cstring>

#include "core/localmap/jcbb.h"
#include "core/sonar/sonar_geometry.h"

namespace atlas {
namespace {

constexpr uint32_t kMagic = 0x4e535441;  // "ATSN"
constexpr uint32_t kVersion = 1;

}  // namespace

SonarLocalMap::SonarLocalMap(const SonarLocalMapOptions& options)
    : o_(options),
      ekf_(options.line_map),
      init_(options.init, options.model),
      sonar_recent_(options.line_map.quality.window) {}

std::unique_ptr<LocalMap> SonarLocalMap::Clone() const {
  return std::make_unique<SonarLocalMap>(*this);
}

void SonarLocalMap::Predict(const Pose2& u) {
  ekf_.Predict(u);
  if (o_.sensors != RangeSensors::kLaser) {
    init_.Predict(u, LineEkfMap::OdometryNoise(u, o_.line_map.odometry));
  }
}

ScanUpdate SonarLocalMap::Update(const LaserScan& scan, bool allow_new_features) {
  if (o_.sensors == RangeSensors::kSonar) return ScanUpdate{};
  return ekf_.Update(scan, allow_new_features);
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
    int best = -1;
    double best_d2 = 0.0, second_d2 = -1.0, best_nu = 0.0;
    Eigen::RowVectorXd best_h(n);
    Vec2 best_foot = Vec2::Zero();
    bool best_edge = false;
    bool near = false, behind = false;
    for (int k = 0; k < nf; ++k) {
      const int ik = 3 + 2 * k;
      const SonarRangePrediction pr =
          PredictSonarRange(robot, mount, x(ik), x(ik + 1), o_.model.edge_incidence);
      if (!pr.echoes()) continue;
      const MapLine& l = lines[k];
      const double t = PositionAlongLine(l.alpha, pr.foot);
      const double ta = PositionAlongLine(l.alpha, l.endpoint_a);
      const double tb = PositionAlongLine(l.alpha, l.endpoint_b);
      if (t < std::min(ta, tb) - o_.update.max_extent_gap ||
          t > std::max(ta, tb) + o_.update.max_extent_gap) {
        continue;
      }
      hk.setZero();
      hk.head<3>() = pr.d_pose;
      hk.segment<2>(ik) = pr.d_line;
      const double s = (hk * p * hk.transpose())(0, 0) + var;
      const double innov = range - pr.range;
      const double d2 = innov * innov / s;
      if (d2 < loose) near = true;
      if (innov > o_.update.behind_sigmas * std::sqrt(s)) behind = true;
      if (!(d2 < gate)) continue;
      if (best < 0 || d2 < best_d2) {
        if (best >= 0) second_d2 = best_d2;
        best = k;
        best_d2 = d2;
        best_nu = innov;
        best_h = hk;
        best_foot = pr.foot;
        best_edge = pr.edge_echo;
      } else if (second_d2 < 0.0 || d2 < second_d2) {
        second_d2 = d2;
      }
    }
    if (best >= 0 && (second_d2 < 0.0 || second_d2 - best_d2 > o_.update.ambiguity_margin)) {
      nu(rows) = best_nu;
      h.row(rows) = best_h;
      r(rows) = var;
      ++rows;
      extents.emplace_back(best, best_foot);
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
    if (ekf_.UpdateWithMeasurements(nu.head(rows), h.topRows(rows), rm)) {
      out.matched = rows;
      out.pairings = std::move(pairings);
      for (const auto& [k, foot] : extents) ekf_.GrowFeatureExtent(k, foot, foot);
    }
  }
  for (const auto& [mount, range] : unexplained) init_.Add(mount, range);
  out.buffered = static_cast<int>(unexplained.size());
  if (allow_new_features && ekf_.Complexity() < ekf_.Capacity()) {
    GroupingDecision d = init_.Decide();
    out.grouping = d.outcome;
    for (InitialisedLine& line : d.lines) {
      if (ekf_.Complexity() >= ekf_.Capacity() || Duplicate(line.line)) continue;
      if (ekf_.AddObservedFeature(line.line) >= 0) {
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
  sonar_recent_.Clear();
  return true;
}

}  // namespace atlas
