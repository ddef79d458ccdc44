#include "core/localmap/quality.h"

#include <gtest/gtest.h>

namespace atlas {
namespace {

TEST(QualityTest, EquationFive) {
  QualityOptions o;
  o.alpha = 0.3;
  o.max_sigma_x = o.max_sigma_y = 0.5;
  o.max_sigma_theta = 0.2;
  const double det_max = 0.25 * 0.25 * 0.04;
  const Mat3 cov = Vec3(0.01, 0.02, 0.001).asDiagonal();
  const double expected = 0.3 * (1.0 - 0.01 * 0.02 * 0.001 / det_max) + 0.7 * 6.0 / 8.0;
  EXPECT_NEAR(QualityMetric(cov, 6, 8, o), expected, 1e-12);
  // Pose worse than acceptable contributes nothing; no observation contributes nothing.
  EXPECT_NEAR(QualityMetric(Mat3::Identity() * 100.0, 0, 0, o), 0.0, 1e-12);
  EXPECT_NEAR(QualityMetric(Mat3::Zero(), 4, 4, o), 1.0, 1e-12);
}

TEST(QualityTest, WindowKeepsOnlyRecentScans) {
  RecentObservations w(3);
  w.Add(5, 5);
  w.Add(4, 0);
  w.Add(2, 1);
  EXPECT_EQ(w.Observations(), 11);
  EXPECT_EQ(w.Matched(), 6);
  w.Add(1, 1);  // the first scan drops out
  EXPECT_EQ(w.Observations(), 7);
  EXPECT_EQ(w.Matched(), 2);
  EXPECT_EQ(w.Size(), 3);
  EXPECT_EQ(w.At(0)[0], 4);
  EXPECT_EQ(w.At(2)[0], 1);
}

}  // namespace
}  // namespace atlas
