#include "tools/monte_carlo/simulated_base.h"

#include <algorithm>
#include <cmath>

namespace atlas::mc {

OdometryNoiseOptions SimulatedBaseOdometry(const WheelOdometryNoiseOptions& wheel) {
  OdometryNoiseOptions o;
  o.track_width = wheel.track_width_m;
  o.wheel_var_per_m = wheel.wheel_noise_per_m;
  o.xy_var_per_m = 0.0;
  o.xy_var_per_rad = 0.0;
  o.theta_var_per_m = 0.0;
  o.theta_var_per_rad = 0.0;
  o.wheel_scale_sigma =
      std::max(std::abs(wheel.left_scale_error), std::abs(wheel.right_scale_error));
  o.track_width_sigma = std::abs(wheel.track_width_error);
  return o;
}

void UseSimulatedWalls(double range_sigma, LineExtractionOptions* o) {
  o->range_sigma = range_sigma;
  o->model_sigma = 0.0;
  o->min_rho_sigma = 0.0;
  o->min_alpha_sigma = 0.0;
}

}  // namespace atlas::mc
