#include "core/geometry/covariance.h"

#include <gtest/gtest.h>

#include <limits>

namespace atlas {
namespace {

TEST(IsPositiveDefiniteCovarianceTest, AcceptsDiagonalAndCorrelated) {
  EXPECT_TRUE(IsPositiveDefiniteCovariance(Mat3::Identity()));
  Mat3 c;
  c << 0.04, 0.01, 0.0001, 0.01, 0.09, -0.0002, 0.0001, -0.0002, 1e-6;
  EXPECT_TRUE(IsPositiveDefiniteCovariance(c));
  // Small variances of very different sizes, as a Genesis edge can carry.
  EXPECT_TRUE(IsPositiveDefiniteCovariance(Vec3(1.0, 1e-4, 1e-10).asDiagonal().toDenseMatrix()));
}

TEST(IsPositiveDefiniteCovarianceTest, RejectsZeroNegativeSingularAndNonFinite) {
  EXPECT_FALSE(IsPositiveDefiniteCovariance(Mat3::Zero()));
  EXPECT_FALSE(IsPositiveDefiniteCovariance(-Mat3::Identity()));
  EXPECT_FALSE(IsPositiveDefiniteCovariance(Mat3::Ones()));  // rank 1
  Mat3 c = Mat3::Identity();
  c(2, 2) = 0.0;
  EXPECT_FALSE(IsPositiveDefiniteCovariance(c));
  c = Mat3::Identity();
  c(0, 1) = c(1, 0) = 2.0;  // indefinite: eigenvalues -1, 3
  EXPECT_FALSE(IsPositiveDefiniteCovariance(c));
  c = Mat3::Identity();
  c(0, 1) = 0.5;  // not symmetric
  EXPECT_FALSE(IsPositiveDefiniteCovariance(c));
  c = Mat3::Identity();
  c(1, 1) = std::numeric_limits<double>::quiet_NaN();
  EXPECT_FALSE(IsPositiveDefiniteCovariance(c));
  c(1, 1) = std::numeric_limits<double>::infinity();
  EXPECT_FALSE(IsPositiveDefiniteCovariance(c));
}

}  // namespace
}  // namespace atlas
