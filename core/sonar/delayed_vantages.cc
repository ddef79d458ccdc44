#include "core/sonar/delayed_vantages.h"

#include <Eigen/Cholesky>
#include <Eigen/Eigenvalues>
#include <algorithm>
#include <cassert>

namespace atlas {
namespace {

void Symmetrize(Eigen::MatrixXd& m) { m = 0.5 * (m + m.transpose()).eval(); }

// d Between(a, b) / da and / db.
void BetweenJacobians(const Pose2& a, const Pose2& b, Mat3& ja, Mat3& jb) {
  const Pose2 ia = Inverse(a);
  ja = ComposeJacobianA(ia, b) * InverseJacobian(a);
  jb = ComposeJacobianB(ia);
}

}  // namespace

void DelayedVantages::Clear() {
  ids_.clear();
  v_.resize(0);
  c_.resize(0, 0);
  vv_.resize(0, 0);
}

int DelayedVantages::IndexOf(int64_t id) const {
  const auto it = std::find(ids_.begin(), ids_.end(), id);
  return it == ids_.end() ? -1 : static_cast<int>(it - ids_.begin());
}

void DelayedVantages::Augment(int64_t id, const Eigen::VectorXd& x, const Eigen::MatrixXd& p) {
  const int n = static_cast<int>(x.size());
  const int m3 = 3 * Size();
  assert(m3 == 0 || c_.cols() == n);
  if (m3 == 0) c_.resize(0, n);
  ids_.push_back(id);
  v_.conservativeResize(m3 + 3);
  v_.tail<3>() = x.head<3>();
  c_.conservativeResize(m3 + 3, n);
  c_.bottomRows(3) = p.topRows(3);
  const Eigen::MatrixXd with_old = c_.topLeftCorner(m3, 3);  // Cov(old v, x_r)
  vv_.conservativeResize(m3 + 3, m3 + 3);
  vv_.topRightCorner(m3, 3) = with_old;
  vv_.bottomLeftCorner(3, m3) = with_old.transpose();
  vv_.bottomRightCorner<3, 3>() = p.topLeftCorner<3, 3>();
}

void DelayedVantages::Keep(const std::vector<int64_t>& ids) {
  std::vector<int> rows;
  std::vector<int64_t> kept;
  for (int i = 0; i < Size(); ++i) {
    if (std::find(ids.begin(), ids.end(), ids_[i]) == ids.end()) continue;
    kept.push_back(ids_[i]);
    for (int k = 0; k < 3; ++k) rows.push_back(3 * i + k);
  }
  if (kept.size() == ids_.size()) return;
  ids_ = std::move(kept);
  v_ = Eigen::VectorXd(v_(rows));
  c_ = Eigen::MatrixXd(c_(rows, Eigen::all));
  vv_ = Eigen::MatrixXd(vv_(rows, rows));
}

void DelayedVantages::Predict(const Mat3& f) {
  if (Size() == 0) return;
  c_.leftCols<3>() = c_.leftCols<3>() * f.transpose();
}

void DelayedVantages::Update(const Eigen::VectorXd& nu, const Eigen::MatrixXd& h,
                             const Eigen::MatrixXd& r, const Eigen::MatrixXd& p) {
  if (Size() == 0) return;
  const Eigen::MatrixXd s = h * p * h.transpose() + r;
  const Eigen::LLT<Eigen::MatrixXd> llt(0.5 * (s + s.transpose()));
  if (llt.info() != Eigen::Success) return;
  // With S = L L^T and W = L^-1 H C^T: K_v = W^T L^-1, V -= W^T W (a symmetric rank update).
  const auto l = llt.matrixL();
  const Eigen::MatrixXd w = l.solve(h * c_.transpose());  // rows x 3m
  v_.noalias() += w.transpose() * l.solve(nu);
  c_.noalias() -= w.transpose() * l.solve(h * p);
  vv_.selfadjointView<Eigen::Lower>().rankUpdate(w.transpose(), -1.0);
  vv_.triangularView<Eigen::StrictlyUpper>() = vv_.transpose();
  for (int i = 0; i < Size(); ++i) v_(3 * i + 2) = WrapAngle(v_(3 * i + 2));
}

void DelayedVantages::Follow(const Eigen::VectorXd& x0, const Eigen::MatrixXd& p0,
                             const Eigen::VectorXd& x1, const Eigen::MatrixXd& p1) {
  if (Size() == 0) return;
  const int n0 = static_cast<int>(x0.size());
  assert(c_.cols() == n0 && x1.size() >= n0);
  const Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> eig(0.5 * (p0 + p0.transpose()));
  const Eigen::VectorXd& lambda = eig.eigenvalues();
  const double tol = 1e-12 * std::max(lambda.cwiseAbs().maxCoeff(), 1e-300);
  Eigen::VectorXd inv(n0);
  for (int k = 0; k < n0; ++k) inv(k) = lambda(k) > tol ? 1.0 / lambda(k) : 0.0;
  const Eigen::MatrixXd g =
      (c_ * eig.eigenvectors()) * inv.asDiagonal() * eig.eigenvectors().transpose();  // C P^+
  Eigen::VectorXd dx = x1.head(n0) - x0;
  for (int k = 2; k < n0; k += 2) dx(k) = WrapAngle(dx(k));
  v_ += g * dx;
  vv_ -= g * (p0 - p1.topLeftCorner(n0, n0)) * g.transpose();
  Symmetrize(vv_);
  c_ = g * p1.topRows(n0);
  for (int i = 0; i < Size(); ++i) v_(3 * i + 2) = WrapAngle(v_(3 * i + 2));
}

void DelayedVantages::AppendFeature(const Eigen::MatrixXd& cov_v) {
  if (Size() == 0) {
    c_.conservativeResize(0, c_.cols() + 2);
    return;
  }
  assert(cov_v.rows() == c_.rows() && cov_v.cols() == 2);
  c_.conservativeResize(Eigen::NoChange, c_.cols() + 2);
  c_.rightCols<2>() = cov_v;
}

void DelayedVantages::Reanchor(const Pose2& robot, const Eigen::MatrixXd& p, const Pose2& pose,
                               const Mat3& pose_cov) {
  const int m = Size();
  const int n = static_cast<int>(p.rows());
  if (m == 0) {
    c_.resize(0, n);
    return;
  }
  // Relative poses rel_i = (-)x_r (+) v_i: d/dx_r = jr_i, d/dv_i = jv (the same for every i);
  // new poses pose (+) rel_i: d/dpose = ja_i, d/drel_i = jb.
  const Mat3 jv = ComposeJacobianB(Inverse(robot));
  const Mat3 jb = ComposeJacobianB(pose);
  Eigen::MatrixXd jr(3 * m, 3), ja(3 * m, 3), cr(3 * m, 3);
  for (int i = 0; i < m; ++i) {
    Mat3 jri, jvi;
    BetweenJacobians(robot, Pose(i), jri, jvi);
    const Pose2 rel = Between(robot, Pose(i));
    jr.block<3, 3>(3 * i, 0) = jri;
    ja.block<3, 3>(3 * i, 0) = ComposeJacobianA(pose, rel);
    cr.block<3, 3>(3 * i, 0) = jv * c_.block<3, 3>(3 * i, 0);
    v_.segment<3>(3 * i) = Compose(pose, rel).ToVector();
  }
  // Cov(rel) = jr P_rr jr^T + jr Cov(x_r, jv v) + Cov(jv v, x_r) jr^T + jv V jv^T, then
  // new V = ja pose_cov ja^T + jb Cov(rel) jb^T (block by block: O(m^2)).
  const Eigen::MatrixXd mixed = jr * cr.transpose();
  const Eigen::MatrixXd rel =
      jr * p.topLeftCorner<3, 3>() * jr.transpose() + mixed + mixed.transpose();
  const Mat3 jbv = jb * jv;
  for (int i = 0; i < m; ++i) {
    for (int k = 0; k < m; ++k) {
      vv_.block<3, 3>(3 * i, 3 * k) = jbv * vv_.block<3, 3>(3 * i, 3 * k) * jbv.transpose() +
                                      jb * rel.block<3, 3>(3 * i, 3 * k) * jb.transpose();
    }
  }
  vv_ += ja * pose_cov * ja.transpose();
  Symmetrize(vv_);
  c_ = Eigen::MatrixXd::Zero(3 * m, n);
  c_.leftCols<3>() = ja * pose_cov;
}

void DelayedVantages::Relative(int i, const Pose2& robot, const Eigen::MatrixXd& p, Pose2& pose,
                               Mat3& cov) const {
  const Pose2 vi = Pose(i);
  Mat3 jr, jv;
  BetweenJacobians(robot, vi, jr, jv);
  pose = Between(robot, vi);
  const Mat3 c_ir = c_.block<3, 3>(3 * i, 0);  // Cov(v_i, x_r)
  const Mat3 cross = jr * c_ir.transpose() * jv.transpose();
  cov = jr * p.topLeftCorner<3, 3>() * jr.transpose() +
        jv * vv_.block<3, 3>(3 * i, 3 * i) * jv.transpose() + cross + cross.transpose();
  cov = 0.5 * (cov + cov.transpose());
}

}  // namespace atlas
