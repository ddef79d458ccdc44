#include "tools/monte_carlo/simulated_base.h"

#include <gtest/gtest.h>

namespace atlas::mc {
namespace {

TEST(SimulatedBase, WheelNoiseOnlyAndCalibrationErrorsAsSigmas) {
  WheelOdometryNoiseOptions wheel;
  wheel.track_width_m = 0.33;
  wheel.wheel_noise_per_m = 4e-6;
  wheel.left_scale_error = 0.0002;
  wheel.right_scale_error = -0.0005;
  wheel.track_width_error = -0.001;
  const OdometryNoiseOptions o = SimulatedBaseOdometry(wheel);
  EXPECT_DOUBLE_EQ(o.track_width, 0.33);
  EXPECT_DOUBLE_EQ(o.wheel_var_per_m, 4e-6);
  EXPECT_EQ(o.xy_var_per_m, 0.0);
  EXPECT_EQ(o.xy_var_per_rad, 0.0);
  EXPECT_EQ(o.theta_var_per_m, 0.0);
  EXPECT_EQ(o.theta_var_per_rad, 0.0);
  EXPECT_DOUBLE_EQ(o.wheel_scale_sigma, 0.0005);
  EXPECT_DOUBLE_EQ(o.track_width_sigma, 0.001);
  EXPECT_EQ(o.Validate(), "");
}

}  // namespace
}  // namespace atlas::mc
