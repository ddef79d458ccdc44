#include "core/localmap/jcbb.h"

#include <gtest/gtest.h>

#include <Eigen/LU>

namespace atlas {
namespace {

// Hand-made association problems: features known exactly in the map, one uncertain robot pose
// shared by all observations, observations (rho, alpha) in the robot frame.
class RobotOnlyCovariance final : public JointCovariance {
 public:
  RobotOnlyCovariance(const Mat3& robot_cov, const std::vector<Mat23>& h)
      : robot_cov_(robot_cov), h_(h) {}
  Mat2 Cross(const CandidatePair& a, const CandidatePair& b) const override {
    return h_[a.tag] * robot_cov_ * h_[b.tag].transpose();
  }

 private:
  Mat3 robot_cov_;
  const std::vector<Mat23>& h_;
};

struct Problem {
  std::vector<Vec2> features;      // map (rho, alpha)
  std::vector<Vec2> observations;  // robot frame
  Pose2 robot;
  Mat3 robot_cov = Mat3::Identity() * 1e-4;
  Mat2 noise = Mat2(Eigen::Vector2d(1e-4, 1e-5).asDiagonal());
  std::vector<CandidatePair> candidates;
  std::vector<Mat23> h;

  JcbbResult Solve(const JcbbOptions& options = JcbbOptions()) {
    const double gate = ChiSquareQuantile(0.99, 2);
    candidates.clear();
    h.clear();
    for (int j = 0; j < static_cast<int>(observations.size()); ++j) {
      for (int k = 0; k < static_cast<int>(features.size()); ++k) {
        LinePrediction p = PredictLine(robot, features[k](0), features[k](1));
        const Vec2 nu = LineInnovation(observations[j], p);
        const Mat2 s = p.d_pose * robot_cov * p.d_pose.transpose() + noise;
        const double d2 = nu.dot(s.inverse() * nu);
        if (d2 >= gate) continue;
        candidates.push_back(CandidatePair{j, k, nu, s, d2, static_cast<int>(h.size())});
        h.push_back(p.d_pose);
      }
    }
    const RobotOnlyCovariance cov(robot_cov, h);
    return Jcbb(static_cast<int>(observations.size()), candidates, cov, options);
  }
};

TEST(JcbbTest, ClearCaseIsUnique) {
  Problem p;
  p.features = {Vec2(3.0, 0.0), Vec2(1.2, std::numbers::pi / 2)};
  p.observations = {Vec2(3.005, 0.001), Vec2(1.19, std::numbers::pi / 2)};
  const JcbbResult r = p.Solve();
  EXPECT_EQ(r.status, AssociationStatus::kUnique);
  EXPECT_EQ(r.pairings, 2);
  EXPECT_EQ(r.feature_of, (std::vector<int>{0, 1}));
}

TEST(JcbbTest, IndividuallyAmbiguousButJointlyUnique) {
  // Two parallel walls 1 m apart, robot very uncertain along x: each observation is
  // individually compatible with both walls, but only one assignment moves the robot
  // consistently for both.
  Problem p;
  p.robot_cov = Vec3(1.0, 0.01, 1e-4).asDiagonal();
  p.features = {Vec2(3.0, 0.0), Vec2(4.0, 0.0)};
  p.observations = {Vec2(3.4, 0.0), Vec2(4.4, 0.0)};
  const JcbbResult r = p.Solve();
  ASSERT_EQ(p.candidates.size(), 4u);  // every pairing passes the individual gate
  EXPECT_EQ(r.status, AssociationStatus::kUnique);
  EXPECT_EQ(r.feature_of, (std::vector<int>{0, 1}));
  EXPECT_NEAR(r.joint_d2, 0.4 * 0.4 / (1.0 + 1e-4) * 1.0, 0.2);
}

TEST(JcbbTest, EquallyGoodRivalsAreRejectedAsAmbiguous) {
  // One observation half way between two parallel walls' predictions.
  Problem p;
  p.robot_cov = Vec3(1.0, 0.01, 1e-4).asDiagonal();
  p.features = {Vec2(3.0, 0.0), Vec2(4.0, 0.0)};
  p.observations = {Vec2(3.5, 0.0)};
  const JcbbResult r = p.Solve();
  EXPECT_EQ(r.status, AssociationStatus::kAmbiguous);
  EXPECT_TRUE(r.ambiguous[0]);
}

TEST(JcbbTest, AmbiguityOnlyTaintsTheObservationsConcerned) {
  // A wall ahead is ambiguous (two parallel candidates), a side wall is not.
  Problem p;
  p.robot_cov = Vec3(1.0, 0.0001, 1e-6).asDiagonal();
  p.features = {Vec2(3.0, 0.0), Vec2(4.0, 0.0), Vec2(1.0, std::numbers::pi / 2)};
  p.observations = {Vec2(3.5, 0.0), Vec2(1.0, std::numbers::pi / 2)};
  const JcbbResult r = p.Solve();
  EXPECT_EQ(r.status, AssociationStatus::kAmbiguous);
  EXPECT_TRUE(r.ambiguous[0]);
  EXPECT_FALSE(r.ambiguous[1]);
  EXPECT_EQ(r.feature_of[1], 2);
}

TEST(JcbbTest, ClearlyWorseRivalIsNotAmbiguity) {
  Problem p;
  p.robot_cov = Vec3(1.0, 0.01, 1e-4).asDiagonal();
  p.features = {Vec2(3.0, 0.0), Vec2(5.5, 0.0)};
  p.observations = {Vec2(3.1, 0.0)};  // d2 0.01 vs 5.8: both gated in, margin 4 separates
  const JcbbResult r = p.Solve();
  EXPECT_EQ(p.candidates.size(), 2u);
  EXPECT_EQ(r.status, AssociationStatus::kUnique);
  EXPECT_EQ(r.feature_of[0], 0);
}

TEST(JcbbTest, SharedFeatureOption) {
  // Two segments of one wall (a door between them) in one scan.
  Problem p;
  p.features = {Vec2(2.0, std::numbers::pi / 2)};
  p.observations = {Vec2(2.0, std::numbers::pi / 2), Vec2(2.003, std::numbers::pi / 2)};
  JcbbOptions o;
  EXPECT_EQ(p.Solve(o).pairings, 2);
  o.allow_shared_features = false;
  EXPECT_EQ(p.Solve(o).pairings, 1);
}

TEST(JcbbTest, WorkIsBoundedByTheNodeBudget) {
  // Ten parallel walls 0.1 m apart, ten observations, robot lost along x: everything is
  // individually compatible with everything.
  Problem p;
  p.robot_cov = Vec3(4.0, 0.01, 1e-4).asDiagonal();
  for (int k = 0; k < 10; ++k) p.features.push_back(Vec2(3.0 + 0.1 * k, 0.0));
  for (int j = 0; j < 10; ++j) p.observations.push_back(Vec2(3.05 + 0.1 * j, 0.0));
  JcbbOptions o;
  o.node_budget = 50;
  const JcbbResult r = p.Solve(o);
  EXPECT_EQ(p.candidates.size(), 100u);
  EXPECT_EQ(r.status, AssociationStatus::kBudgetExhausted);
  EXPECT_LE(r.nodes, 50);
}

TEST(JcbbTest, ChiSquareQuantiles) {
  EXPECT_NEAR(ChiSquareQuantile(0.95, 1), 3.841, 2e-3);
  EXPECT_NEAR(ChiSquareQuantile(0.99, 2), 9.210, 2e-3);
  EXPECT_NEAR(ChiSquareQuantile(0.95, 3), 7.815, 0.05);  // Wilson-Hilferty, worst at low dof
  EXPECT_NEAR(ChiSquareQuantile(0.99, 20), 37.566, 5e-2);
  EXPECT_NEAR(ChiSquareQuantile(0.025, 150), 117.98, 0.2);
  EXPECT_NEAR(ChiSquareQuantile(0.975, 150), 185.80, 0.2);
}

}  // namespace
}  // namespace atlas
