#include "core/common/normal_quantile.h"

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

namespace atlas {
namespace {

TEST(NormalQuantile, KnownValues) {
  EXPECT_NEAR(NormalQuantile(0.975), 1.959963985, 1e-8);
  EXPECT_NEAR(NormalQuantile(0.5), 0.0, 1e-12);
  EXPECT_NEAR(NormalQuantile(0.001), -3.090232306, 1e-8);
  EXPECT_NEAR(NormalQuantile(0.999), 3.090232306, 1e-8);
}

TEST(NormalQuantile, InvertsTheCdfInEveryBranch) {
  for (double p : {1e-12, 1e-6, 0.01, 0.02, 0.3, 0.5, 0.7, 0.98, 0.99, 1 - 1e-6}) {
    const double x = NormalQuantile(p);
    EXPECT_NEAR(0.5 * std::erfc(-x / std::numbers::sqrt2), p, 1e-12 + 1e-9 * p) << p;
  }
  EXPECT_TRUE(std::isfinite(NormalQuantile(0.0)));
  EXPECT_TRUE(std::isfinite(NormalQuantile(1.0)));
}

}  // namespace
}  // namespace atlas
