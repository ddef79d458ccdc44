#include "core/sonar/delayed_vantages.h"

#include <gtest/gtest.h>

#include <Eigen/Cholesky>
#include <Eigen/LU>
#include <cmath>
#include <numbers>
#include <random>

#include "core/sonar/sonar_local_map.h"
#include "core/testing/degrees.h"
#include "core/testing/fake_sonar_ring.h"

namespace atlas {
namespace {

Eigen::MatrixXd RandomCovariance(int n, std::mt19937_64& rng) {
  std::normal_distribution<double> n01;
  Eigen::MatrixXd a(n, n + 2);
  for (int i = 0; i < a.rows(); ++i) {
    for (int k = 0; k < a.cols(); ++k) a(i, k) = 0.1 * n01(rng);
  }
  return a * a.transpose();
}

// The delayed states mirror an EKF update on the augmented state (s, v): Update (given the
// update) and Follow (given only the EKF before and after) both equal the augmented
// filter's result.
TEST(DelayedVantages, UpdateAndFollowMatchTheAugmentedFilter) {
  std::mt19937_64 rng(7);
  std::normal_distribution<double> n01;
  const int n = 7, m = 2, rows = 3;  // robot + 2 lines, 2 vantage points
  // Two vantage points: the robot pose now and after a noisy motion.
  Eigen::VectorXd x(n);
  for (int i = 0; i < n; ++i) x(i) = 0.5 * n01(rng);
  Eigen::MatrixXd p = RandomCovariance(n, rng);
  DelayedVantages dv;
  for (int i = 0; i < m; ++i) {
    if (i > 0) {
      const Pose2 r0{x(0), x(1), x(2)}, u{0.4, -0.1, 0.3};
      const Mat3 f = ComposeJacobianA(r0, u);
      const Mat3 prr0 = p.topLeftCorner<3, 3>();
      x.head<3>() = Compose(r0, u).ToVector();
      p.topLeftCorner<3, 3>() = f * prr0 * f.transpose() + 0.01 * Mat3::Identity();
      p.topRightCorner(3, n - 3) = f * p.topRightCorner(3, n - 3);
      p.bottomLeftCorner(n - 3, 3) = p.topRightCorner(3, n - 3).transpose();
      dv.Predict(f);
      // Cov(v_0, x_r) = Cov(x_r before, F x_r before + noise) = P_rr F^T.
      EXPECT_LT((dv.CrossCovariance().block<3, 3>(0, 0) - prr0 * f.transpose()).norm(), 1e-12);
    }
    dv.Augment(i, x, p);
  }
  // The augmented filter's joint covariance and vantage means.
  Eigen::MatrixXd pa(n + 3 * m, n + 3 * m);
  pa.topLeftCorner(n, n) = p;
  pa.bottomLeftCorner(3 * m, n) = dv.CrossCovariance();
  pa.topRightCorner(n, 3 * m) = dv.CrossCovariance().transpose();
  pa.bottomRightCorner(3 * m, 3 * m) = dv.Covariance();
  Eigen::VectorXd va(3 * m);
  for (int i = 0; i < m; ++i) va.segment<3>(3 * i) = dv.Pose(i).ToVector();

  Eigen::MatrixXd h(rows, n);
  for (int i = 0; i < rows; ++i) {
    for (int k = 0; k < n; ++k) h(i, k) = n01(rng);
  }
  const Eigen::MatrixXd r = 0.01 * Eigen::MatrixXd::Identity(rows, rows);
  Eigen::VectorXd nu(rows);
  for (int i = 0; i < rows; ++i) nu(i) = 0.1 * n01(rng);
  Eigen::MatrixXd ha = Eigen::MatrixXd::Zero(rows, n + 3 * m);
  ha.leftCols(n) = h;
  const Eigen::MatrixXd s = ha * pa * ha.transpose() + r;
  const Eigen::MatrixXd k = pa * ha.transpose() * s.inverse();
  const Eigen::MatrixXd pa1 = pa - k * ha * pa;
  const Eigen::VectorXd dxa = k * nu;

  DelayedVantages exact = dv;
  exact.Update(nu, h, r, pa.topLeftCorner(n, n));
  DelayedVantages followed = dv;
  const Eigen::VectorXd x0 = x;
  Eigen::VectorXd x1 = x0 + dxa.head(n);
  followed.Follow(x0, pa.topLeftCorner(n, n), x1, pa1.topLeftCorner(n, n));
  for (const DelayedVantages* d : {&exact, &followed}) {
    EXPECT_LT((d->CrossCovariance() - pa1.bottomLeftCorner(3 * m, n)).cwiseAbs().maxCoeff(), 1e-9);
    EXPECT_LT((d->Covariance() - pa1.bottomRightCorner(3 * m, 3 * m)).cwiseAbs().maxCoeff(), 1e-9);
    for (int i = 0; i < m; ++i) {
      EXPECT_LT((d->Pose(i).ToVector() - (va + dxa.tail(3 * m)).segment<3>(3 * i)).norm(), 1e-9);
    }
  }
}

// Reanchor keeps the vantage points' poses relative to the robot and their covariance.
TEST(DelayedVantages, ReanchorKeepsRelativePoses) {
  std::mt19937_64 rng(3);
  const int n = 5;
  Eigen::VectorXd x(n);
  x << 1.0, 2.0, 0.3, 2.0, 0.5;
  Eigen::MatrixXd p = RandomCovariance(n, rng);
  DelayedVantages dv;
  dv.Augment(0, x, p);
  // The robot moves on (Predict, with noise) and a second vantage point is added.
  const Pose2 u{0.5, 0.1, 0.2};
  const Pose2 r0{x(0), x(1), x(2)};
  const Mat3 f = ComposeJacobianA(r0, u);
  const Pose2 r1 = Compose(r0, u);
  x.head<3>() = r1.ToVector();
  p.topLeftCorner<3, 3>() = f * p.topLeftCorner<3, 3>() * f.transpose() + 1e-3 * Mat3::Identity();
  p.topRightCorner(3, n - 3) = f * p.topRightCorner(3, n - 3);
  p.bottomLeftCorner(n - 3, 3) = p.topRightCorner(3, n - 3).transpose();
  dv.Predict(f);
  dv.Augment(1, x, p);
  Pose2 rel_before[2];
  Mat3 cov_before[2];
  for (int i = 0; i < 2; ++i) dv.Relative(i, r1, p, rel_before[i], cov_before[i]);
  EXPECT_NEAR(cov_before[1].norm(), 0.0, 1e-12);  // the current pose itself
  EXPECT_NEAR(cov_before[0](2, 2), 1e-3, 1e-9);   // one step's noise

  const Pose2 placed{-3.0, 4.0, 2.0};
  const Mat3 placed_cov = Vec3(0.04, 0.01, 0.002).asDiagonal();
  dv.Reanchor(r1, p, placed, placed_cov);
  Eigen::MatrixXd p_new = p;
  p_new.topLeftCorner<3, 3>() = placed_cov;
  p_new.topRightCorner(3, n - 3).setZero();
  p_new.bottomLeftCorner(n - 3, 3).setZero();
  for (int i = 0; i < 2; ++i) {
    Pose2 rel;
    Mat3 cov;
    dv.Relative(i, placed, p_new, rel, cov);
    EXPECT_NEAR(rel.x, rel_before[i].x, 1e-12);
    EXPECT_NEAR(rel.y, rel_before[i].y, 1e-12);
    EXPECT_NEAR(rel.theta, rel_before[i].theta, 1e-12);
    EXPECT_LT((cov - cov_before[i]).cwiseAbs().maxCoeff(), 1e-12);
  }
  EXPECT_LT((dv.CrossCovariance().rightCols(n - 3)).cwiseAbs().maxCoeff(), 1e-15);
}

// Monte Carlo reference for delayed decision making's covariance (Fig. 9): a robot drives along
// a wall with noisy odometry (sampled from the filter's own Q(u)) and noisy sonar (the model's
// range sigma), and the wall is initialised from the returns of past vantage points. Over the
// runs, the errors of (robot pose, new line) at initialisation, whitened by each run's joint
// covariance from the EKF, must have unit sample covariance: the line's covariance and its
// cross covariance with the robot pose are those of the sample.
// The whitened sample covariance of (robot pose, new line) errors at the line's initialisation
// over `runs` seeded runs (see below).
Eigen::Matrix<double, 5, 5> WhitenedInitialisationErrors(bool delayed_states, int runs, int& used) {
  SonarLocalMapOptions o;
  o.init.delayed_states = delayed_states;
  EXPECT_EQ(o.Validate(), "");
  o.line_map.capacity = 4;
  o.line_map.odometry.wheel_var_per_m = 2e-5;
  o.line_map.odometry.theta_var_per_m = 3e-4;  // heading noise: the past poses matter
  o.model.range_sigma = 0.01;
  o.model.range_sigma_per_m = 0.0;
  o.model.model_sigma = 0.0;
  o.model.edge_incidence = 0.0;
  o.init.edge_echoes = false;
  o.init.min_rho_sigma = 0.0;
  o.init.min_alpha_sigma = 0.0;
  o.init.iterations = 16;  // one wall: a few RANSAC hypotheses find it (fast under sanitizers)
  SonarTransducer left, ahead;
  left.pose = Pose2{0.0, 0.2, 90 * kDeg};
  ahead.pose = Pose2{0.1, 0.18, 75 * kDeg};
  for (SonarTransducer* t : {&left, &ahead}) {
    t->beam_width = 25 * kDeg;
    t->max_range = 6.0;
  }
  const std::vector<SonarTransducer> ring = {left, ahead};
  const std::vector<sim::Wall> walls = {{Vec2(-5.0, 2.0), Vec2(20.0, 2.0)}};
  const Vec2 wall(2.0, std::numbers::pi / 2);
  const Pose2 u_true{0.2, 0.0, 0.02};

  Eigen::Matrix<double, 5, 5> sample = Eigen::Matrix<double, 5, 5>::Zero();
  used = 0;
  for (int run = 0; run < runs; ++run) {
    std::mt19937_64 rng(1000 + run);
    std::normal_distribution<double> n01;
    SonarLocalMap map(o);
    Pose2 truth{};
    bool done = false;
    for (int step = 0; step < 40 && !done; ++step) {
      const SonarUpdate up =
          map.UpdateSonar(FireFakeSonarRing(walls, ring, truth, 0.01, rng), ring, true);
      if (up.added > 0) {
        const Eigen::VectorXd& x = map.Ekf().State();
        const Eigen::MatrixXd& p = map.Ekf().Covariance();
        Eigen::Matrix<double, 5, 1> e;
        e << x(0) - truth.x, x(1) - truth.y, WrapAngle(x(2) - truth.theta), x(3) - wall(0),
            WrapAngle(x(4) - wall(1));
        Eigen::Matrix<double, 5, 5> c;
        c << p.topLeftCorner<3, 3>(), p.block<3, 2>(0, 3), p.block<2, 3>(3, 0), p.block<2, 2>(3, 3);
        const Eigen::Matrix<double, 5, 5> l = c.llt().matrixL();
        const Eigen::Matrix<double, 5, 1> w = l.triangularView<Eigen::Lower>().solve(e);
        sample += w * w.transpose();
        ++used;
        done = true;
      }
      const Mat3 q = LineEkfMap::OdometryNoise(u_true, o.line_map.odometry);
      const Vec3 noise = Mat3(q.llt().matrixL()) * Vec3(n01(rng), n01(rng), n01(rng));
      truth = Compose(truth, u_true);
      map.Predict(Pose2{u_true.x + noise(0), u_true.y + noise(1), u_true.theta + noise(2)});
    }
  }
  return sample / std::max(used, 1);
}

TEST(DelayedVantages, InitialisedLineCovarianceMatchesMonteCarlo) {
  constexpr int kRuns = 400;
  int used = 0;
  const Eigen::Matrix<double, 5, 5> sample = WhitenedInitialisationErrors(true, kRuns, used);
  ASSERT_GT(used, kRuns * 9 / 10);
  // Diagonal: sample variance / filter variance; off-diagonal: sample correlation of the
  // whitened errors. Standard errors about sqrt(2 / N) = 0.07 and sqrt(1 / N) = 0.05.
  for (int i = 0; i < 5; ++i) {
    for (int k = 0; k < 5; ++k) {
      EXPECT_NEAR(sample(i, k), i == k ? 1.0 : 0.0, 0.25) << "entry " << i << "," << k << "\n"
                                                          << sample;
    }
  }
}

// The same case with the earlier approximation (the line's robot-frame covariance through the
// inverse model as if observed from the current pose): far from the sample (this is what the
// test above guards against).
TEST(DelayedVantages, IndependentVantageApproximationIsInconsistent) {
  int used = 0;
  const Eigen::Matrix<double, 5, 5> sample = WhitenedInitialisationErrors(false, 100, used);
  ASSERT_GT(used, 90);
  EXPECT_GT((sample - Eigen::Matrix<double, 5, 5>::Identity()).cwiseAbs().maxCoeff(), 1.0)
      << sample;
}

}  // namespace
}  // namespace atlas
