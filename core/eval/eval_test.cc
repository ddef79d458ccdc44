#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <vector>

#include "core/eval/error_stats.h"
#include "core/eval/reference_score.h"
#include "core/eval/relations_metric.h"
#include "core/eval/timed_trajectory.h"

namespace atlas::eval {
namespace {

constexpr double kPi = std::numbers::pi;
constexpr double kDegPerRad = 180.0 / kPi;

Time At(double s) { return FromSeconds(s); }

TEST(ErrorStatsTest, HandComputed) {
  const std::vector<double> e = {3.0, 4.0};
  const ErrorStats s = Summarize(e);
  EXPECT_EQ(s.count, 2);
  EXPECT_DOUBLE_EQ(s.mean, 3.5);
  EXPECT_DOUBLE_EQ(s.stddev, 0.5);
  EXPECT_DOUBLE_EQ(s.mean_squared, 12.5);  // (9 + 16) / 2
  EXPECT_DOUBLE_EQ(s.stddev_squared, 3.5);
  EXPECT_DOUBLE_EQ(s.rmse, std::sqrt(12.5));
  EXPECT_DOUBLE_EQ(s.max, 4.0);
  const ErrorStats empty = Summarize(std::vector<double>{});
  EXPECT_EQ(empty.count, 0);
  EXPECT_EQ(empty.mean, 0.0);
}

TEST(TimedTrajectoryTest, NearestWithinTolerance) {
  const TimedTrajectory t(
      {{At(3.0), {3, 0, 0}}, {At(1.0), {1, 0, 0}}, {At(2.0), {2, 0, 0}}, {At(2.0), {2.5, 0, 0}}});
  ASSERT_EQ(t.size(), 4u);
  EXPECT_EQ(t.poses()[0].stamp, At(1.0));  // sorted
  const Duration ms = std::chrono::milliseconds(1);
  EXPECT_DOUBLE_EQ(t.PoseAt(At(1.0009), ms)->x, 1.0);
  EXPECT_DOUBLE_EQ(t.PoseAt(At(2.9991), ms)->x, 3.0);
  EXPECT_FALSE(t.PoseAt(At(1.0011), ms).has_value());
  EXPECT_FALSE(t.PoseAt(At(0.5), ms).has_value());
  EXPECT_FALSE(t.PoseAt(At(3.5), ms).has_value());
  EXPECT_DOUBLE_EQ(t.PoseAt(At(2.0), ms)->x, 2.0);     // first of equal stamps
  EXPECT_DOUBLE_EQ(t.PoseAt(At(2.0004), ms)->x, 2.0);  // from above, still the first
  EXPECT_DOUBLE_EQ(t.PoseAt(At(1.6), std::chrono::seconds(1))->x, 2.0);  // nearer
  EXPECT_DOUBLE_EQ(t.PoseAt(At(1.4), std::chrono::seconds(1))->x, 1.0);
  EXPECT_FALSE(TimedTrajectory().PoseAt(At(1.0), ms).has_value());
}

// Ground truth: a loop of 40 poses; relations between every pose and the ones 1 and 7 later.
std::vector<TimedPose> Loop() {
  std::vector<TimedPose> out;
  for (int i = 0; i < 40; ++i) {
    const double a = 2 * kPi * i / 40;
    out.push_back(
        {At(100.0 + 0.5 * i), Pose2{5 * std::cos(a), 5 * std::sin(a), WrapAngle(a + kPi / 2)}});
  }
  return out;
}
std::vector<Relation> RelationsOf(const std::vector<TimedPose>& truth) {
  std::vector<Relation> out;
  for (size_t i = 0; i < truth.size(); ++i) {
    for (size_t k : {1u, 7u}) {
      if (i + k < truth.size()) {
        out.push_back(
            {truth[i].stamp, truth[i + k].stamp, Between(truth[i].pose, truth[i + k].pose)});
      }
    }
  }
  return out;
}

TEST(RelationsMetricTest, PerfectEstimateScoresZeroInAnyFrame) {
  const auto truth = Loop();
  const auto relations = RelationsOf(truth);
  // The estimate lives in another global frame: relative poses are unchanged.
  std::vector<TimedPose> moved = truth;
  for (TimedPose& p : moved) p.pose = Compose(Pose2{12.0, -3.0, 2.0}, p.pose);
  const TimedTrajectory estimate(moved);
  const RelationsScore s = ScoreRelations(relations, BetweenPosesOf(estimate));
  EXPECT_EQ(s.matched, static_cast<int64_t>(relations.size()));
  EXPECT_EQ(s.unmatched, 0);
  EXPECT_LT(s.translation_m.max, 1e-9);
  EXPECT_LT(s.rotation_deg.max, 1e-9);
}

TEST(RelationsMetricTest, HandComputedError) {
  const std::vector<Relation> rel = {{At(1), At(2), Pose2{1, 0, 0}}};
  const TimedTrajectory estimate(
      {{At(1), {10, 10, kPi / 2}}, {At(2), {10 - 0.4, 11.3, kPi / 2 + 0.1}}});
  // Estimated delta = (1.3, 0.4, 0.1); error = (1,0,0) (-) delta = (0.3, 0.4, 0.1).
  const RelationsScore s = ScoreRelations(rel, BetweenPosesOf(estimate));
  ASSERT_EQ(s.matched, 1);
  EXPECT_NEAR(s.translation_m.mean, 0.5, 1e-9);
  EXPECT_NEAR(s.rotation_deg.mean, 0.1 * kDegPerRad, 1e-9);
  EXPECT_NEAR(s.translation_m.mean_squared, 0.25, 1e-9);
}

TEST(RelationsMetricTest, ErrorIsExpressedInTheRelationsEndFrame) {
  // Relation: turn by 90 deg and move 1 m ahead. Estimate: the same but 0.2 m too far.
  const Relation rel{At(0), At(1), Pose2{1, 0, kPi / 2}};
  const RelationError e = RelationErrorOf(rel, Pose2{1.2, 0, kPi / 2});
  EXPECT_NEAR(e.translation_m, 0.2, 1e-12);
  EXPECT_NEAR(e.rotation_deg, 0.0, 1e-9);
}

TEST(RelationsMetricTest, RotationalErrorIsWrapped) {
  const Relation rel{At(0), At(1), Pose2{0, 0, 3.1}};
  const RelationError e = RelationErrorOf(rel, Pose2{0, 0, -3.1});
  EXPECT_NEAR(e.rotation_deg, (2 * kPi - 6.2) * kDegPerRad, 1e-9);  // 4.8 deg, not 355
}

TEST(RelationsMetricTest, UnmatchedStampsAreCountedNotScored) {
  const TimedTrajectory estimate({{At(1), {0, 0, 0}}, {At(2), {1, 0, 0}}, {At(3), {5, 0, 0}}});
  const std::vector<Relation> rel = {
      {At(1.0009), At(1.9991), Pose2{1, 0, 0}},  // within 1 ms: matched, error 0
      {At(1.0), At(2.0015), Pose2{1, 0, 0}},     // t2 1.5 ms off: unmatched
      {At(0.0), At(1.0), Pose2{1, 0, 0}},        // no pose at t1
  };
  const RelationsScore s = ScoreRelations(rel, BetweenPosesOf(estimate));
  EXPECT_EQ(s.matched, 1);
  EXPECT_EQ(s.unmatched, 2);
  ASSERT_EQ(s.errors.size(), 1u);
  EXPECT_EQ(s.errors[0].relation, 0u);
  EXPECT_NEAR(s.translation_m.mean, 0.0, 1e-12);
}

TEST(RelationsMetricTest, AnyRelativePoseLookupCanBeScored) {
  // An estimate that only knows relative poses (as the atlas graph will): a constant 1 %
  // over-estimate of every distance.
  const auto truth = Loop();
  const auto relations = RelationsOf(truth);
  const TimedTrajectory t(truth);
  const RelativePoseLookup scaled = [&t](Time a, Time b) -> std::optional<Pose2> {
    const auto pa = t.PoseAt(a, kDefaultMatchTolerance), pb = t.PoseAt(b, kDefaultMatchTolerance);
    if (!pa || !pb) return std::nullopt;
    Pose2 d = Between(*pa, *pb);
    d.x *= 1.01;
    d.y *= 1.01;
    return d;
  };
  const RelationsScore s = ScoreRelations(relations, scaled);
  EXPECT_EQ(s.matched, static_cast<int64_t>(relations.size()));
  // Each error is 1 % of that relation's length.
  for (const RelationError& e : s.errors) {
    const Pose2& d = relations[e.relation].delta;
    EXPECT_NEAR(e.translation_m, 0.01 * std::hypot(d.x, d.y), 1e-9);
  }
  EXPECT_GT(s.translation_m.mean, 0.0);
}

TEST(ReferenceScoreTest, OptionsValidate) {
  ReferenceScoreOptions o;
  EXPECT_EQ(o.Validate(), "");
  o.step_count = 3;
  EXPECT_NE(o.Validate(), "");
  o.segment_length_m = 0.0;
  EXPECT_EQ(o.Validate(), "");
  o.step_count = 0;
  EXPECT_NE(o.Validate(), "");
}

TEST(ReferenceScoreTest, BestRigidAlignmentRecoversATransform) {
  const auto truth = Loop();
  const Pose2 t{3.0, -7.0, -2.5};
  std::vector<Pose2> from, to;
  for (const TimedPose& p : truth) {
    from.push_back(p.pose);
    to.push_back(Compose(t, p.pose));
  }
  const Pose2 a = BestRigidAlignment(from, to);
  EXPECT_NEAR(a.x, t.x, 1e-9);
  EXPECT_NEAR(a.y, t.y, 1e-9);
  EXPECT_NEAR(a.theta, t.theta, 1e-9);
}

TEST(ReferenceScoreTest, RigidlyMovedEstimateHasNoError) {
  const auto truth = Loop();
  std::vector<TimedPose> moved = truth;
  for (TimedPose& p : moved) p.pose = Compose(Pose2{-4.0, 9.0, 1.0}, p.pose);
  const ReferenceScore s = ScoreAgainstReference(TimedTrajectory(moved), TimedTrajectory(truth),
                                                 ReferenceScoreOptions{});
  EXPECT_EQ(s.matched, 40);
  EXPECT_GT(s.pairs, 30);
  EXPECT_LT(s.rpe_translation_m.max, 1e-9);
  EXPECT_LT(s.ate_translation_m.max, 1e-9);
  EXPECT_LT(s.ate_rotation_deg.max, 1e-7);
}

TEST(ReferenceScoreTest, ScaleErrorOnAStraightLine) {
  // Reference: 1 m steps along x. Estimate: 10 % too long, plus one pose without a reference.
  std::vector<TimedPose> ref, est;
  for (int i = 0; i <= 10; ++i) {
    ref.push_back({At(i), Pose2{1.0 * i, 0, 0}});
    est.push_back({At(i), Pose2{1.1 * i, 0, 0}});
  }
  est.push_back({At(20), Pose2{0, 0, 0}});
  ReferenceScoreOptions by_step;
  by_step.step_count = 1;
  by_step.segment_length_m = 0.0;
  ReferenceScore s = ScoreAgainstReference(TimedTrajectory(est), TimedTrajectory(ref), by_step);
  EXPECT_EQ(s.matched, 11);
  EXPECT_EQ(s.unmatched, 1);
  EXPECT_EQ(s.pairs, 10);
  EXPECT_NEAR(s.rpe_translation_m.mean, 0.1, 1e-9);
  EXPECT_NEAR(s.rpe_translation_m.stddev, 0.0, 1e-9);

  ReferenceScoreOptions by_distance;
  by_distance.segment_length_m = 2.5;  // pairs (i, i + 3): 3 m apart, 0.3 m error
  s = ScoreAgainstReference(TimedTrajectory(est), TimedTrajectory(ref), by_distance);
  EXPECT_EQ(s.pairs, 8);
  EXPECT_NEAR(s.rpe_translation_m.mean, 0.3, 1e-9);

  // ATE: best alignment centres the two lines (x = 5 vs 5.5); errors |0.1 i - 0.5|.
  EXPECT_NEAR(s.alignment.x, -0.5, 1e-9);
  EXPECT_NEAR(s.ate_translation_m.max, 0.5, 1e-9);
  EXPECT_NEAR(s.ate_translation_m.mean, 0.3 * 10 / 11, 1e-9);  // (0.5+0.4+..+0+..+0.5) / 11
  EXPECT_NEAR(s.reference_path_m, 10.0, 1e-9);

  // Pairs farther apart than the path is long: none, and the caller must say so (atlas-eval
  // fails rather than print 0 +- 0 over no pair).
  by_distance.segment_length_m = 10.5;
  s = ScoreAgainstReference(TimedTrajectory(est), TimedTrajectory(ref), by_distance);
  EXPECT_EQ(s.pairs, 0);
  EXPECT_EQ(s.rpe_translation_m.count, 0);
  by_step.step_count = 11;
  s = ScoreAgainstReference(TimedTrajectory(est), TimedTrajectory(ref), by_step);
  EXPECT_EQ(s.pairs, 0);
}

}  // namespace
}  // namespace atlas::eval
