#include "tools/monte_carlo/nees_band.h"

#include <gtest/gtest.h>

#include "core/localmap/jcbb.h"

namespace atlas::mc {
namespace {

TEST(NeesBand, BandOfTheMeanOverRuns) {
  const NeesBand one = MeanNeesBand(3, 1);
  // About the chi-square(3) 2.5 % and 97.5 % points, 0.216 and 9.348 (ChiSquareQuantile is an
  // approximation).
  EXPECT_NEAR(one.lo, 0.216, 0.05);
  EXPECT_NEAR(one.hi, 9.348, 0.05);
  const NeesBand fifty = MeanNeesBand(3, 50);
  EXPECT_DOUBLE_EQ(fifty.lo, ChiSquareQuantile(0.025, 150) / 50);
  EXPECT_DOUBLE_EQ(fifty.hi, ChiSquareQuantile(0.975, 150) / 50);
  // More runs: a narrower band around the dof.
  EXPECT_GT(fifty.lo, one.lo);
  EXPECT_LT(fifty.hi, one.hi);
  EXPECT_LT(fifty.lo, 3.0);
  EXPECT_GT(fifty.hi, 3.0);
}

TEST(NeesBand, MeansOverTheStepsEveryRunHas) {
  const StepMeans m = MeanPerStep({{1.0, 2.0, 3.0, 9.0}, {3.0, kNoNees, 5.0}});
  ASSERT_EQ(m.mean.size(), 3u);
  EXPECT_DOUBLE_EQ(m.mean[0], 2.0);
  EXPECT_DOUBLE_EQ(m.mean[2], 4.0);
  EXPECT_EQ(m.known, (std::vector<bool>{true, false, true}));
  EXPECT_TRUE(MeanPerStep({}).mean.empty());
}

TEST(NeesBand, SummaryCountsKnownStepsInsideAndBelow) {
  StepMeans m;
  m.mean = {0.1, 2.0, 50.0, 4.0, 12.0};
  m.known = {true, true, false, true, true};
  const BandSummary s = SummarizeInBand(m, NeesBand{1.0, 5.0});
  EXPECT_EQ(s.steps, 4);
  EXPECT_EQ(s.inside, 2);  // 2.0 and 4.0
  EXPECT_EQ(s.below, 3);   // 0.1, 2.0, 4.0
  EXPECT_DOUBLE_EQ(s.mean, (0.1 + 2.0 + 4.0 + 12.0) / 4);
  EXPECT_DOUBLE_EQ(s.max, 12.0);
  EXPECT_DOUBLE_EQ(s.InsidePercent(), 50.0);
  const BandSummary none = SummarizeInBand(StepMeans{}, NeesBand{1.0, 5.0});
  EXPECT_EQ(none.steps, 0);
  EXPECT_DOUBLE_EQ(none.mean, 0.0);
  EXPECT_DOUBLE_EQ(none.InsidePercent(), 0.0);
}

}  // namespace
}  // namespace atlas::mc
