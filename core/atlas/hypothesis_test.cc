#include "core/atlas/hypothesis.h"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>

namespace atlas {
namespace {

TEST(HypothesisQuality, Eq5) {
  HypothesisQualityOptions o;
  o.alpha = 0.3;
  o.sigma_x = 0.5;
  o.sigma_y = 0.4;
  o.sigma_theta = 0.1;
  const double det_star = 0.25 * 0.16 * 0.01;
  const Mat3 cov = Vec3(0.05, 0.04, 0.002).asDiagonal();
  const double expect = 0.3 * (1 - 0.05 * 0.04 * 0.002 / det_star) + 0.7 * 0.75;
  EXPECT_NEAR(HypothesisQuality(cov, 0.75, o), expect, 1e-12);
  // Too uncertain: first term clamps at 0.
  EXPECT_NEAR(HypothesisQuality(Mat3::Identity() * 10, 1.0, o), 0.7, 1e-12);
  EXPECT_NEAR(HypothesisQuality(Mat3::Zero(), 1.0, o), 1.0, 1e-12);
  // A covariance that is not finite carries no certainty (NaN is not a determinant of 0).
  Mat3 nan_cov = cov;
  nan_cov(0, 0) = std::numeric_limits<double>::quiet_NaN();
  EXPECT_NEAR(HypothesisQuality(nan_cov, 0.75, o), 0.7 * 0.75, 1e-12);
  EXPECT_NEAR(HypothesisQuality(Mat3::Identity() * INFINITY, 0.75, o), 0.7 * 0.75, 1e-12);
}

TEST(QualityWindow, SlidesOverTheLastScans) {
  QualityWindow w(3);
  EXPECT_EQ(w.Explanation(0.25), 0.25);
  w.Add({10, 10, 0, false});
  w.Add({10, 5, 0, false});
  w.Add({10, 0, 0, false});
  EXPECT_NEAR(w.Explanation(0), 0.5, 1e-12);
  w.Add({10, 0, 0, false});  // the first (10 of 10) drops out
  EXPECT_NEAR(w.Explanation(0), 5.0 / 30.0, 1e-12);
  w.Add({4, 9, 0, false});  // matched clamped to observations
  EXPECT_EQ(w.Matched(), 4);
  EXPECT_EQ(w.Observations(), 24);
  QualityWindow r(1);
  r.Restore(3, w.Ring(), w.Head(), w.Size());
  EXPECT_EQ(r.Matched(), w.Matched());
  EXPECT_EQ(r.Observations(), w.Observations());
}

Hypothesis Juvenile(int steps, double q, bool bootstrapped) {
  Hypothesis h;
  h.state = HypothesisState::kJuvenile;
  h.steps = steps;
  h.q = q;
  h.bootstrapped = bootstrapped;
  return h;
}

Hypothesis Mature(double q) {
  Hypothesis h;
  h.state = HypothesisState::kMature;
  h.q = q;
  return h;
}

TEST(HypothesisStateMachine, JuvenileWaitsOutProbation) {
  LifecycleOptions o;
  o.bootstrap_scans = 3;
  o.probation_scans = 6;
  for (int s = 0; s < 6; ++s)
    EXPECT_EQ(JudgeJuvenile(Juvenile(s, 0.99, true), 0.1, false, o), JuvenileVerdict::kContinue);
}

TEST(HypothesisStateMachine, JuvenileKilledWhenBootstrapFails) {
  LifecycleOptions o;
  EXPECT_EQ(JudgeJuvenile(Juvenile(2, 0.99, false), 0.1, true, o), JuvenileVerdict::kDelete);
}

TEST(HypothesisStateMachine, JuvenileMaturesOnlyWhenBeatingEveryMature) {
  LifecycleOptions o;
  o.bootstrap_scans = 3;
  o.probation_scans = 6;
  EXPECT_EQ(JudgeJuvenile(Juvenile(6, 0.8, true), 0.7, false, o), JuvenileVerdict::kMature);
  EXPECT_EQ(JudgeJuvenile(Juvenile(6, 0.7, true), 0.7, false, o), JuvenileVerdict::kDelete);
  EXPECT_EQ(JudgeJuvenile(Juvenile(6, 0.6, true), 0.7, false, o), JuvenileVerdict::kDelete);
  // Without any mature hypothesis (best q negative) a bootstrapped juvenile matures.
  EXPECT_EQ(JudgeJuvenile(Juvenile(6, 0.0, true), -1.0, false, o), JuvenileVerdict::kMature);
  // Never bootstrapped: deleted at the end of probation however good q looks.
  EXPECT_EQ(JudgeJuvenile(Juvenile(6, 0.99, false), 0.1, false, o), JuvenileVerdict::kDelete);
}

TEST(HypothesisStateMachine, MatureFailsAfterConsecutiveBadSteps) {
  LifecycleOptions o;
  o.q_fail = 0.4;
  o.fail_steps = 3;
  Hypothesis h = Mature(0.3);
  EXPECT_FALSE(UpdateFailing(&h, o));
  EXPECT_FALSE(UpdateFailing(&h, o));
  h.q = 0.5;  // one good step resets the count
  EXPECT_FALSE(UpdateFailing(&h, o));
  h.q = 0.3;
  EXPECT_FALSE(UpdateFailing(&h, o));
  EXPECT_FALSE(UpdateFailing(&h, o));
  EXPECT_TRUE(UpdateFailing(&h, o));
  Hypothesis j;  // juveniles never "fail" this way
  j.q = 0.0;
  for (int i = 0; i < 5; ++i) EXPECT_FALSE(UpdateFailing(&j, o));
}

TEST(HypothesisStateMachine, MatureLaggingFarBehindTheDominantFails) {
  LifecycleOptions o;
  o.retire_margin = 0.2;
  o.lag_steps = 3;
  Hypothesis h = Mature(0.5);  // above q_fail: the absolute rule never fires
  EXPECT_FALSE(UpdateLagging(&h, false, 0.75, o));
  EXPECT_FALSE(UpdateLagging(&h, false, 0.75, o));
  EXPECT_FALSE(UpdateLagging(&h, false, 0.65, o));  // within the margin: the count restarts
  EXPECT_EQ(h.lagging_steps, 0);
  EXPECT_FALSE(UpdateLagging(&h, false, 0.75, o));
  EXPECT_FALSE(UpdateLagging(&h, false, 0.75, o));
  EXPECT_TRUE(UpdateLagging(&h, false, 0.75, o));
  EXPECT_FALSE(UpdateFailing(&h, o));
  Hypothesis d = Mature(0.1);  // the dominant one never lags
  for (int i = 0; i < 5; ++i) EXPECT_FALSE(UpdateLagging(&d, true, 0.9, o));
  Hypothesis j;  // nor do juveniles
  j.q = 0.0;
  for (int i = 0; i < 5; ++i) EXPECT_FALSE(UpdateLagging(&j, false, 0.9, o));
  LifecycleOptions bad = o;
  bad.lag_steps = 0;
  EXPECT_NE(bad.Validate(), "");
  bad = o;
  bad.retire_margin = -0.1;
  EXPECT_NE(bad.Validate(), "");
}

TEST(HypothesisStateMachine, DominantIsBestMature) {
  std::vector<Hypothesis> hs(4);
  hs[0].state = HypothesisState::kMature;
  hs[0].q = 0.6;
  hs[0].id = 1;
  hs[1].state = HypothesisState::kJuvenile;  // juveniles never dominate
  hs[1].q = 0.99;
  hs[1].id = 2;
  hs[2].state = HypothesisState::kMature;
  hs[2].q = 0.7;
  hs[2].id = 3;
  hs[3].state = HypothesisState::kRetired;
  hs[3].q = 0.95;
  hs[3].id = 4;
  EXPECT_EQ(DominantIndex(hs), 2);
  hs[0].q = 0.7;  // tie goes to the older
  EXPECT_EQ(DominantIndex(hs), 0);
  hs[0].state = hs[2].state = HypothesisState::kJuvenile;
  EXPECT_EQ(DominantIndex(hs), -1);
}

TEST(HypothesisStateMachine, PreviousDominantStaysWithinTheSwitchMargin) {
  std::vector<Hypothesis> hs(3);
  for (int i = 0; i < 3; ++i) {
    hs[i].state = HypothesisState::kMature;
    hs[i].id = i + 1;
  }
  hs[0].q = 0.80;
  hs[1].q = 0.60;
  hs[1].dominant = true;  // the previous step's
  hs[2].q = 0.50;
  EXPECT_EQ(DominantIndex(hs), 0);       // no hysteresis: the best q
  EXPECT_EQ(DominantIndex(hs, 0.1), 0);  // 0.2 behind: switches
  hs[1].q = 0.75;
  EXPECT_EQ(DominantIndex(hs, 0.1), 1);  // 0.05 behind: stays
  EXPECT_EQ(DominantIndex(hs, 0.0), 0);
  hs[1].state = HypothesisState::kRetired;  // a retired one never dominates
  EXPECT_EQ(DominantIndex(hs, 0.1), 0);
}

TEST(Options, Validate) {
  EXPECT_EQ(HypothesisQualityOptions{}.Validate(), "");
  EXPECT_EQ(LifecycleOptions{}.Validate(), "");
  HypothesisQualityOptions q;
  q.alpha = 1.5;
  EXPECT_NE(q.Validate(), "");
  LifecycleOptions l;
  l.probation_scans = l.bootstrap_scans;
  EXPECT_NE(l.Validate(), "");
}

}  // namespace
}  // namespace atlas
