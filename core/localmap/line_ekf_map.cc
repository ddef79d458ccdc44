#include "core/localmap/line_ekf_map.h"

#include <Eigen/Cholesky>
#include <Eigen/LU>
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <numbers>

#include "core/localmap/jcbb.h"
#include "core/localmap/line_extraction.h"

namespace atlas {
namespace {

// Measurement Jacobian blocks of one candidate pairing.
struct PairJacobian {
  Mat23 h_pose;
  Mat2 h_line;
  int k = 0;                // feature index
  Mat23 g = Mat23::Zero();  // h_pose P_rr + h_line P_kr
};

class EkfJointCovariance final : public JointCovariance {
 public:
  EkfJointCovariance(const Eigen::MatrixXd& p, const std::vector<PairJacobian>& h) : P_(p), h_(h) {}
  Mat2 Cross(const CandidatePair& a, const CandidatePair& b) const override {
    const PairJacobian& ha = h_[a.tag];
    const PairJacobian& hb = h_[b.tag];
    const int kb = 3 + 2 * hb.k;
    const Eigen::Matrix<double, 2, 2> m =
        ha.h_pose * P_.block<3, 2>(0, kb) + ha.h_line * P_.block<2, 2>(3 + 2 * ha.k, kb);
    return ha.g * hb.h_pose.transpose() + m * hb.h_line.transpose();
  }

 private:
  const Eigen::MatrixXd& P_;
  const std::vector<PairJacobian>& h_;
};

double Sq(double v) { return v * v; }

void Symmetrize(Eigen::MatrixXd& p) {
  const Eigen::Index n = p.rows();
  for (Eigen::Index c = 0; c < n; ++c) {
    for (Eigen::Index r = c + 1; r < n; ++r) {
      const double v = 0.5 * (p(r, c) + p(c, r));
      p(r, c) = v;
      p(c, r) = v;
    }
  }
}

// Per-thread buffers of UpdateWithLines: no heap allocation per scan once warm.
struct UpdateScratch {
  std::vector<CandidatePair> cands;
  std::vector<CandidatePair> wide;  // candidates between the gate and the recovery gate
  std::vector<PairJacobian> jac;
  std::vector<char> near_feature;
  std::vector<int> used;
  Eigen::VectorXd nu;
  Eigen::MatrixXd s, pht, k_t;
  Eigen::LLT<Eigen::MatrixXd> llt;
};

// Whether the segment z (map-frame, canonical) lies on the line (rho, alpha): its direction
// within duplicate_alpha and its middle within duplicate_rho of the line. Measured at the
// segment, not at the map-frame origin, where a small heading error moves rho by its lever arm.
bool NearLine(const ObservedLine& z, double rho, double alpha, const AssociationOptions& o) {
  const double dalpha = WrapAngle(z.alpha - alpha);
  const bool parallel = std::abs(dalpha) < o.duplicate_alpha ||
                        std::abs(WrapAngle(dalpha - std::numbers::pi)) < o.duplicate_alpha;
  const Vec2 mid = 0.5 * (z.endpoint_a + z.endpoint_b);
  const double offset = mid.x() * std::cos(alpha) + mid.y() * std::sin(alpha) - rho;
  return parallel && std::abs(offset) < o.duplicate_rho;
}

double ProjectedPosition(double alpha, const Vec2& p) { return PositionAlongLine(alpha, p); }

// Byte image helpers.
class Writer {
 public:
  template <typename T>
  void Put(const T& v) {
    const char* p = reinterpret_cast<const char*>(&v);
    out.append(p, sizeof(T));
  }
  std::string out;
};

class Reader {
 public:
  explicit Reader(const std::string& s) : s_(s) {}
  template <typename T>
  bool Get(T& v) {
    if (s_.size() - pos_ < sizeof(T)) return false;
    std::memcpy(&v, s_.data() + pos_, sizeof(T));
    pos_ += sizeof(T);
    return true;
  }
  bool AtEnd() const { return pos_ == s_.size(); }

 private:
  const std::string& s_;
  size_t pos_ = 0;
};

constexpr uint32_t kMagic = 0x4d4c5441;  // "ATLM"
constexpr uint32_t kVersion = 1;

}  // namespace

LineEkfMap::LineEkfMap(const LocalMapOptions& options)
    : options_(options),
      x_(Eigen::VectorXd::Zero(3)),
      P_(Eigen::MatrixXd::Zero(3, 3)),
      recent_(options.quality.window) {}

std::unique_ptr<LocalMap> LineEkfMap::Clone() const { return std::make_unique<LineEkfMap>(*this); }

namespace {

// Q over (dx, dy, dtheta) of a step of chord s and turn dth whose left and right wheel distances
// have variances var_l, var_r (track width b).
Mat3 WheelNoise(double s, double dth, double b, double var_l, double var_r) {
  Mat2 wheel_cov;  // over (arc, dtheta)
  wheel_cov << 0.25 * (var_l + var_r), 0.5 * (var_r - var_l) / b, 0.5 * (var_r - var_l) / b,
      (var_l + var_r) / (b * b);
  const double c = std::cos(0.5 * dth), sn = std::sin(0.5 * dth);
  Eigen::Matrix<double, 3, 2> j;
  j << c, -0.5 * s * sn, sn, 0.5 * s * c, 0.0, 1.0;
  return j * wheel_cov * j.transpose();
}

double SignedChord(const Pose2& u) {
  const double d = std::hypot(u.x, u.y);
  return u.x >= 0.0 ? d : -d;
}

}  // namespace

Mat3 LineEkfMap::OdometryNoise(const Pose2& u, const OdometryNoiseOptions& o) {
  const double d = std::hypot(u.x, u.y);
  const double s = SignedChord(u);
  const double dth = u.theta;
  const double b = o.track_width;
  const double d_l = s - 0.5 * dth * b, d_r = s + 0.5 * dth * b;
  const double var_l = o.wheel_var_per_m * std::abs(d_l) + Sq(o.wheel_scale_sigma * d_l);
  const double var_r = o.wheel_var_per_m * std::abs(d_r) + Sq(o.wheel_scale_sigma * d_r);
  Mat3 q = WheelNoise(s, dth, b, var_l, var_r);
  const double turn = std::abs(dth);
  q(0, 0) += o.xy_var_per_m * d + o.xy_var_per_rad * turn;
  q(1, 1) += o.xy_var_per_m * d + o.xy_var_per_rad * turn;
  q(2, 2) += o.theta_var_per_m * d + o.theta_var_per_rad * turn + Sq(o.track_width_sigma * dth);
  return q;
}

Mat3 LineEkfMap::PredictNoise(const Pose2& u) {
  OdometryNoiseOptions white = options_.odometry;
  white.wheel_scale_sigma = 0.0;
  white.track_width_sigma = 0.0;
  Mat3 q = OdometryNoise(u, white);
  const OdometryNoiseOptions& o = options_.odometry;
  if (o.wheel_scale_sigma <= 0.0 && o.track_width_sigma <= 0.0) return q;
  // Calibration errors repeat every step: since the last corrected pose their errors add up
  // (standard deviation sigma * accumulated distance), so each step adds the growth of that
  // variance, not an independent share.
  const double s = SignedChord(u);
  const double b = o.track_width;
  const double d_l = std::abs(s - 0.5 * u.theta * b), d_r = std::abs(s + 0.5 * u.theta * b);
  const double var_l = Sq(o.wheel_scale_sigma) * (Sq(calib_left_ + d_l) - Sq(calib_left_));
  const double var_r = Sq(o.wheel_scale_sigma) * (Sq(calib_right_ + d_r) - Sq(calib_right_));
  q += WheelNoise(s, u.theta, b, var_l, var_r);
  const double turn = std::abs(u.theta);
  q(2, 2) += Sq(o.track_width_sigma) * (Sq(calib_turn_ + turn) - Sq(calib_turn_));
  calib_left_ += d_l;
  calib_right_ += d_r;
  calib_turn_ += turn;
  return q;
}

void LineEkfMap::ClearCalibrationDrift() { calib_left_ = calib_right_ = calib_turn_ = 0.0; }

void LineEkfMap::Predict(const Pose2& u) { Predict(u, PredictNoise(u)); }

void LineEkfMap::Predict(const Pose2& u, const Mat3& q) {
  const Pose2 r = Robot();
  const Mat3 f = ComposeJacobianA(r, u);
  const Mat3 g = ComposeJacobianB(r);
  const Pose2 moved = Compose(r, u);
  x_(0) = moved.x;
  x_(1) = moved.y;
  x_(2) = moved.theta;
  const int n = static_cast<int>(x_.size());
  P_.topLeftCorner<3, 3>() = f * P_.topLeftCorner<3, 3>() * f.transpose() + g * q * g.transpose();
  if (n > 3) {
    P_.topRightCorner(3, n - 3) = f * P_.topRightCorner(3, n - 3);
    P_.bottomLeftCorner(n - 3, 3) = P_.topRightCorner(3, n - 3).transpose();
  }
}

ScanUpdate LineEkfMap::Update(const LaserScan& scan, bool allow_new_features) {
  return UpdateWithLines(ExtractRobotFrameLines(scan, options_.extraction), allow_new_features);
}

ScanUpdate LineEkfMap::Update(const ScanObservation& observation, bool allow_new_features) {
  return UpdateWithLines(observation.RobotFrameLines(options_.extraction), allow_new_features);
}

ScanUpdate LineEkfMap::UpdateWithLines(const std::vector<ObservedLine>& observed,
                                       bool allow_new_features) {
  ScanUpdate out;
  const int m = static_cast<int>(observed.size());
  const int nf = Complexity();
  out.observations = m;
  last_observations_ = observed;
  last_association_.assign(m, -1);
  last_recovered_ = false;
  const Pose2 robot = Robot();
  const AssociationOptions& ao = options_.association;
  const double gate = ChiSquareQuantile(ao.individual_gate, 2);
  const double loose_gate = ChiSquareQuantile(ao.new_feature_gate, 2);
  const bool recovery = ao.recovery_gate > 0.0;
  const double wide_gate = recovery ? ChiSquareQuantile(ao.recovery_gate, 2) : gate;

  thread_local UpdateScratch scratch;
  std::vector<CandidatePair>& strict = scratch.cands;
  std::vector<CandidatePair>& wide = scratch.wide;
  std::vector<PairJacobian>& jac = scratch.jac;
  std::vector<char>& near_feature = scratch.near_feature;
  strict.clear();
  wide.clear();
  jac.clear();
  near_feature.assign(m, 0);
  const Mat3 prr = P_.topLeftCorner<3, 3>();
  for (int j = 0; j < m; ++j) {
    const ObservedLine& z = observed[j];
    const Vec2 zv(z.rho, z.alpha);
    const Vec2 ea = robot.TransformPoint(z.endpoint_a), eb = robot.TransformPoint(z.endpoint_b);
    for (int k = 0; k < nf; ++k) {
      const int ik = 3 + 2 * k;
      LinePrediction pred = PredictLine(robot, x_(ik), x_(ik + 1));
      const Vec2 nu = LineInnovation(zv, pred);
      const Eigen::Matrix<double, 2, 3> prk = P_.block<2, 3>(ik, 0);
      const Mat23 g = pred.d_pose * prr + pred.d_line * prk;
      const Mat2 s = g * pred.d_pose.transpose() +
                     (pred.d_pose * prk.transpose() + pred.d_line * P_.block<2, 2>(ik, ik)) *
                         pred.d_line.transpose() +
                     z.cov;
      const Mat2 s_sym = 0.5 * (s + s.transpose());
      const double det = s_sym.determinant();
      if (!(det > 0.0)) continue;
      const double d2 = nu.dot(s_sym.inverse() * nu);
      if (d2 < loose_gate) near_feature[j] = 1;
      if (!(d2 < wide_gate)) continue;
      // Segment-extent check along the feature's line.
      const double alpha = x_(ik + 1);
      const double t0 = ProjectedPosition(alpha, ea), t1 = ProjectedPosition(alpha, eb);
      const double s0 = ProjectedPosition(alpha, extents_[k].a);
      const double s1 = ProjectedPosition(alpha, extents_[k].b);
      const double gap =
          std::max(std::min(s0, s1) - std::max(t0, t1), std::min(t0, t1) - std::max(s0, s1));
      if (gap > ao.max_extent_gap) continue;
      const CandidatePair pair{j, k, nu, s_sym, d2, static_cast<int>(jac.size())};
      if (d2 < gate) {
        strict.push_back(pair);
      } else {
        wide.push_back(pair);  // the recovery pass adds the strict ones
      }
      jac.push_back(PairJacobian{pred.d_pose, pred.d_line, k, g});
    }
  }

  JcbbOptions jo;
  jo.joint_gate = ao.joint_gate;
  jo.node_budget = ao.node_budget;
  jo.allow_shared_features = ao.allow_shared_features;
  jo.ambiguity_margin = ao.ambiguity_margin;
  EkfJointCovariance cross(P_, jac);
  JcbbResult assoc = Jcbb(m, strict, cross, jo);
  const std::vector<CandidatePair>* active = &strict;
  if (recovery && assoc.pairings == 0 && !wide.empty()) {
    wide.insert(wide.end(), strict.begin(), strict.end());
    jo.joint_gate = ao.recovery_gate;
    JcbbResult recovered = Jcbb(m, wide, cross, jo);
    // A lone pairing at the wide gate is unverified (AssociationOptions::recovery_min_pairings).
    // A result that pairs nothing is kept, as before that option: its ambiguities still bar new
    // features.
    if (recovered.pairings == 0 || recovered.pairings >= ao.recovery_min_pairings) {
      assoc = std::move(recovered);
      active = &wide;
      last_recovered_ = assoc.pairings > 0;
    }
  }
  const std::vector<CandidatePair>& cands = *active;
  out.ambiguous = assoc.status != AssociationStatus::kUnique;

  std::vector<int>& used = scratch.used;  // candidate indices applied
  used.clear();
  if (assoc.status != AssociationStatus::kBudgetExhausted) {
    for (int j = 0; j < m; ++j) {
      if (assoc.pair_of[j] >= 0 && !assoc.ambiguous[j]) used.push_back(assoc.pair_of[j]);
    }
  }

  const int n = static_cast<int>(x_.size());
  const int q = static_cast<int>(used.size());
  if (q > 0) {
    Eigen::VectorXd& nu = scratch.nu;
    Eigen::MatrixXd& s = scratch.s;
    Eigen::MatrixXd& pht = scratch.pht;
    Eigen::MatrixXd& k_t = scratch.k_t;
    nu.resize(2 * q);
    s.resize(2 * q, 2 * q);
    pht.resize(n, 2 * q);
    for (int a = 0; a < q; ++a) {
      const CandidatePair& ca = cands[used[a]];
      const PairJacobian& ja = jac[ca.tag];
      nu.segment<2>(2 * a) = ca.innovation;
      s.block<2, 2>(2 * a, 2 * a) = ca.S;
      for (int b = a + 1; b < q; ++b) {
        const Mat2 c = cross.Cross(ca, cands[used[b]]);
        s.block<2, 2>(2 * a, 2 * b) = c;
        s.block<2, 2>(2 * b, 2 * a) = c.transpose();
      }
      pht.middleCols<2>(2 * a) = P_.leftCols<3>() * ja.h_pose.transpose() +
                                 P_.middleCols<2>(3 + 2 * ja.k) * ja.h_line.transpose();
    }
    Eigen::LLT<Eigen::MatrixXd>& llt = scratch.llt;
    llt.compute(s);
    if (llt.info() == Eigen::Success) {
      k_t = pht.transpose();
      llt.solveInPlace(k_t);  // (P H^T S^-1)^T
      x_.noalias() += k_t.transpose() * nu;
      P_.noalias() -= pht * k_t;
      Symmetrize(P_);
      x_(2) = WrapAngle(x_(2));
      for (int k = 0; k < nf; ++k) x_(4 + 2 * k) = WrapAngle(x_(4 + 2 * k));
      const Pose2 updated = Robot();
      for (int a = 0; a < q; ++a) {
        const CandidatePair& ca = cands[used[a]];
        last_association_[ca.observation] = ids_[ca.feature];
        GrowExtent(ca.feature, ObservedLineToParent(updated, observed[ca.observation]));
      }
      out.matched = q;
      ClearCalibrationDrift();
    }
  }

  if (allow_new_features && assoc.status != AssociationStatus::kBudgetExhausted) {
    std::vector<int> fresh;
    for (int j = 0; j < m; ++j) {
      if (last_association_[j] >= 0 || assoc.ambiguous[j] || near_feature[j]) continue;
      if (observed[j].Length() < ao.new_feature_min_length) continue;
      fresh.push_back(j);
    }
    std::stable_sort(fresh.begin(), fresh.end(),
                     [&](int a, int b) { return observed[a].Length() > observed[b].Length(); });
    const int first_new = Complexity();
    for (int j : fresh) {
      if (Complexity() >= Capacity()) break;
      // Two segments of one new wall in the same scan make one feature; a line close to a
      // feature's line is that feature's wall, however the association went.
      bool duplicate = false;
      for (int k = first_new; k < Complexity() && !duplicate; ++k) {
        duplicate = SquaredDistanceTo(observed[j], k) < loose_gate;
      }
      const ObservedLine in_map = ObservedLineToParent(Robot(), observed[j]);
      for (int k = 0; k < Complexity() && !duplicate; ++k) {
        duplicate = NearLine(in_map, x_(3 + 2 * k), x_(4 + 2 * k), ao);
      }
      if (duplicate) continue;
      AddFeature(observed[j]);
      last_association_[j] = ids_.back();
      ++out.added;
    }
  }
  recent_.Add(out.observations, out.matched);
  return out;
}

bool LineEkfMap::UpdateWithMeasurements(const Eigen::VectorXd& nu, const Eigen::MatrixXd& h,
                                        const Eigen::MatrixXd& r) {
  const int n = static_cast<int>(x_.size());
  if (nu.size() == 0 || h.cols() != n || h.rows() != nu.size() || r.rows() != nu.size() ||
      r.cols() != nu.size()) {
    return false;
  }
  const Eigen::MatrixXd pht = P_ * h.transpose();
  const Eigen::MatrixXd s = h * pht + r;
  const Eigen::LLT<Eigen::MatrixXd> llt(0.5 * (s + s.transpose()));
  if (llt.info() != Eigen::Success) return false;
  const Eigen::MatrixXd k_t = llt.solve(pht.transpose());
  x_ += k_t.transpose() * nu;
  P_.noalias() -= pht * k_t;
  Symmetrize(P_);
  x_(2) = WrapAngle(x_(2));
  for (int k = 0; k < Complexity(); ++k) x_(4 + 2 * k) = WrapAngle(x_(4 + 2 * k));
  ClearCalibrationDrift();
  return true;
}

int LineEkfMap::AddObservedFeature(const ObservedLine& z) {
  if (Complexity() >= Capacity()) return -1;
  AddFeature(z);
  return ids_.back();
}

void LineEkfMap::GrowFeatureExtent(int k, const Vec2& a, const Vec2& b) {
  if (k < 0 || k >= Complexity()) return;
  ObservedLine z;
  z.endpoint_a = a;
  z.endpoint_b = b;
  GrowExtent(k, z);
}

double LineEkfMap::SquaredDistanceTo(const ObservedLine& z, int k) const {
  const int ik = 3 + 2 * k;
  LinePrediction pred = PredictLine(Robot(), x_(ik), x_(ik + 1));
  const Vec2 nu = LineInnovation(Vec2(z.rho, z.alpha), pred);
  Eigen::Matrix<double, 2, 5> h;
  h << pred.d_pose, pred.d_line;
  Eigen::Matrix<double, 5, 5> p;
  p << P_.topLeftCorner<3, 3>(), P_.block<3, 2>(0, ik), P_.block<2, 3>(ik, 0),
      P_.block<2, 2>(ik, ik);
  const Mat2 s = h * p * h.transpose() + z.cov;
  return nu.dot(s.ldlt().solve(nu));
}

void LineEkfMap::AddFeature(const ObservedLine& z) {
  const Pose2 r = Robot();
  const LineTransform t = LineToParent(r, z.rho, z.alpha);
  const int n = static_cast<int>(x_.size());
  const ObservedLine in_map = ObservedLineToParent(r, z);
  AppendFeature(t.line,
                t.d_pose * P_.topLeftCorner<3, 3>() * t.d_pose.transpose() +
                    t.d_line * z.cov * t.d_line.transpose(),
                t.d_pose * P_.topLeftCorner(3, n), in_map.endpoint_a, in_map.endpoint_b);
}

int LineEkfMap::AddJointFeature(const Vec2& line, const Mat2& cov, const Eigen::MatrixXd& cross,
                                const Vec2& a, const Vec2& b) {
  if (Complexity() >= Capacity() || cross.rows() != 2 || cross.cols() != x_.size()) return -1;
  AppendFeature(line, cov, cross, a, b);
  return ids_.back();
}

void LineEkfMap::AppendFeature(const Vec2& line, const Mat2& cov, const Eigen::MatrixXd& cross,
                               const Vec2& a, const Vec2& b) {
  const int n = static_cast<int>(x_.size());
  x_.conservativeResize(n + 2);
  x_(n) = line(0);
  x_(n + 1) = WrapAngle(line(1));
  P_.conservativeResize(n + 2, n + 2);
  P_.block(n, 0, 2, n) = cross;
  P_.block(0, n, n, 2) = cross.transpose();
  P_.block<2, 2>(n, n) = cov;
  ids_.push_back(next_id_++);
  extents_.push_back(Extent{a, b});
}

void LineEkfMap::GrowExtent(int k, const ObservedLine& z_map) {
  const double rho = x_(3 + 2 * k), alpha = x_(4 + 2 * k);
  double lo = 1e300, hi = -1e300;
  for (const Vec2& p : {extents_[k].a, extents_[k].b, z_map.endpoint_a, z_map.endpoint_b}) {
    const double t = PositionAlongLine(alpha, p);
    lo = std::min(lo, t);
    hi = std::max(hi, t);
  }
  extents_[k].a = PointOnLine(rho, alpha, lo);
  extents_[k].b = PointOnLine(rho, alpha, hi);
}

UncertainPose LineEkfMap::RobotPose() const {
  return UncertainPose{Robot(), P_.topLeftCorner<3, 3>()};
}

void LineEkfMap::ResetRobotPose(const UncertainPose& pose) {
  ClearCalibrationDrift();
  x_(0) = pose.mean.x;
  x_(1) = pose.mean.y;
  x_(2) = WrapAngle(pose.mean.theta);
  const int n = static_cast<int>(x_.size());
  P_.topLeftCorner<3, 3>() = 0.5 * (pose.cov + pose.cov.transpose());
  if (n > 3) {
    P_.topRightCorner(3, n - 3).setZero();
    P_.bottomLeftCorner(n - 3, 3).setZero();
  }
}

void LineEkfMap::SetRobotPoseFromFeatures(const Pose2& pose, const Mat3& observation_cov,
                                          const std::vector<int>& feature_index,
                                          const Eigen::Matrix<double, 3, Eigen::Dynamic>& d_lines) {
  const int n = static_cast<int>(x_.size());
  Eigen::MatrixXd j = Eigen::MatrixXd::Zero(3, n);  // d pose / d state (features only)
  for (size_t a = 0; a < feature_index.size(); ++a) {
    const int k = feature_index[a];
    if (k < 0 || k >= Complexity() || static_cast<int>(2 * a + 1) >= d_lines.cols()) continue;
    j.middleCols<2>(3 + 2 * k) += d_lines.middleCols<2>(2 * a);
    // d_lines is with respect to the canonical line of Lines(); the state may hold (-rho, .).
    if (x_(3 + 2 * k) < 0.0) j.col(3 + 2 * k) = -j.col(3 + 2 * k).eval();
  }
  const Eigen::MatrixXd cross = j * P_;  // 3 x n, robot rows of J P are zero in J
  x_(0) = pose.x;
  x_(1) = pose.y;
  x_(2) = WrapAngle(pose.theta);
  Mat3 prr = (cross * j.transpose()).eval() + observation_cov;
  P_.topRows(3) = cross;
  P_.leftCols(3) = cross.transpose();
  P_.topLeftCorner<3, 3>() = 0.5 * (prr + prr.transpose());
  ClearCalibrationDrift();
}

double LineEkfMap::Quality() const {
  return QualityMetric(P_.topLeftCorner<3, 3>(), recent_.Matched(), recent_.Observations(),
                       options_.quality);
}

int LineEkfMap::FeatureIndex(int id) const {
  for (int k = 0; k < Complexity(); ++k) {
    if (ids_[k] == id) return k;
  }
  return -1;
}

std::vector<MapLine> LineEkfMap::Lines() const {
  std::vector<MapLine> lines;
  lines.reserve(Complexity());
  for (int k = 0; k < Complexity(); ++k) {
    MapLine l;
    l.id = ids_[k];
    l.rho = x_(3 + 2 * k);
    l.alpha = x_(4 + 2 * k);
    l.cov = P_.block<2, 2>(3 + 2 * k, 3 + 2 * k);
    if (CanonicalizeLine(l.rho, l.alpha)) l.cov(0, 1) = l.cov(1, 0) = -l.cov(0, 1);
    const double ta = PositionAlongLine(l.alpha, extents_[k].a);
    const double tb = PositionAlongLine(l.alpha, extents_[k].b);
    l.endpoint_a = PointOnLine(l.rho, l.alpha, ta);
    l.endpoint_b = PointOnLine(l.rho, l.alpha, tb);
    lines.push_back(l);
  }
  return lines;
}

std::string LineEkfMap::Serialize() const {
  Writer w;
  w.Put(kMagic);
  w.Put(kVersion);
  const int32_t nf = Complexity();
  w.Put(nf);
  w.Put(static_cast<int32_t>(next_id_));
  for (int i = 0; i < x_.size(); ++i) w.Put(x_(i));
  for (int r = 0; r < P_.rows(); ++r) {
    for (int c = 0; c < P_.cols(); ++c) w.Put(P_(r, c));
  }
  for (int k = 0; k < nf; ++k) {
    w.Put(static_cast<int32_t>(ids_[k]));
    w.Put(extents_[k].a.x());
    w.Put(extents_[k].a.y());
    w.Put(extents_[k].b.x());
    w.Put(extents_[k].b.y());
  }
  w.Put(static_cast<int32_t>(recent_.Size()));
  for (int i = 0; i < recent_.Size(); ++i) {
    w.Put(static_cast<int32_t>(recent_.At(i)[0]));
    w.Put(static_cast<int32_t>(recent_.At(i)[1]));
  }
  return w.out;
}

bool LineEkfMap::Deserialize(const std::string& bytes) {
  Reader r(bytes);
  uint32_t magic = 0, version = 0;
  int32_t nf = 0, next_id = 0;
  if (!r.Get(magic) || magic != kMagic || !r.Get(version) || version != kVersion) return false;
  // At most `capacity` features (the memory and time per frame are bounded by it): an image
  // with more, or one made with a larger capacity, is refused.
  if (!r.Get(nf) || !r.Get(next_id) || nf < 0 || nf > options_.capacity || next_id < 0 ||
      next_id == INT32_MAX)
    return false;
  const int n = 3 + 2 * nf;
  if (bytes.size() < static_cast<size_t>(n) * (n + 1) * sizeof(double)) return false;
  Eigen::VectorXd x(n);
  Eigen::MatrixXd p(n, n);
  for (int i = 0; i < n; ++i) {
    if (!r.Get(x(i)) || !std::isfinite(x(i))) return false;
  }
  for (int i = 0; i < n; ++i) {
    for (int c = 0; c < n; ++c) {
      if (!r.Get(p(i, c)) || !std::isfinite(p(i, c))) return false;
    }
  }
  for (int i = 0; i < n; ++i) {
    if (p(i, i) < 0.0) return false;
    for (int c = 0; c < i; ++c) {
      if (std::abs(p(i, c) - p(c, i)) > 1e-9 * (1.0 + std::abs(p(i, c)))) return false;
    }
  }
  std::vector<int> ids(nf);
  std::vector<Extent> ext(nf);
  for (int k = 0; k < nf; ++k) {
    int32_t id = 0;
    double v[4];
    if (!r.Get(id) || id < 0 || id >= next_id) return false;
    for (double& e : v) {
      if (!r.Get(e) || !std::isfinite(e)) return false;
    }
    for (int q = 0; q < k; ++q) {
      if (ids[q] == id) return false;
    }
    ids[k] = id;
    ext[k] = Extent{Vec2(v[0], v[1]), Vec2(v[2], v[3])};
  }
  int32_t window_size = 0;
  if (!r.Get(window_size) || window_size < 0 || window_size > RecentObservations::kMaxWindow)
    return false;
  RecentObservations recent(options_.quality.window);
  for (int i = 0; i < window_size; ++i) {
    int32_t o = 0, mt = 0;
    // Counts of one scan (features extracted): bounded, so that the window's sums cannot
    // overflow.
    if (!r.Get(o) || !r.Get(mt) || o < 0 || o > (1 << 20) || mt < 0 || mt > o) return false;
    recent.Add(o, mt);
  }
  if (!r.AtEnd()) return false;
  x_ = std::move(x);
  P_ = std::move(p);
  ids_ = std::move(ids);
  extents_ = std::move(ext);
  next_id_ = next_id;
  recent_ = recent;
  last_association_.clear();
  last_observations_.clear();
  ClearCalibrationDrift();
  return true;
}

}  // namespace atlas
