#include "drivers/agilex/wheel_odometry.h"

#include <algorithm>
#include <cassert>
#include <cmath>

namespace atlas::agilex {

std::string WheelOdometryOptions::Validate() const {
  if (!(track_width_m > 0.0) || !std::isfinite(track_width_m)) {
    return "track_width_m must be a positive number of metres";
  }
  if (!(max_speed_mps > 0.0) || !std::isfinite(max_speed_mps)) {
    return "max_speed_mps must be a positive speed in m/s";
  }
  if (!(slack_m >= 0.0) || !std::isfinite(slack_m)) return "slack_m must be >= 0 metres";
  return {};
}

WheelOdometryIntegrator::WheelOdometryIntegrator(const WheelOdometryOptions& options)
    : options_(options) {
  assert(options_.Validate().empty());
}

OdometryStep WheelOdometryIntegrator::Update(Time stamp, const WheelDistances& counters) {
  ++updates_;
  const Time previous_stamp = last_stamp_;
  const WheelDistances previous = last_;
  const bool had_reference = have_reference_;
  last_ = counters;
  last_stamp_ = stamp;
  have_reference_ = true;
  sample_.stamp = stamp;
  if (!had_reference) return OdometryStep::kFirst;

  const double dt = std::max(0.0, ToSeconds(stamp - previous_stamp));
  const double dl = (static_cast<int64_t>(counters.left_mm) - previous.left_mm) * 1e-3;
  const double dr = (static_cast<int64_t>(counters.right_mm) - previous.right_mm) * 1e-3;
  const double limit = options_.max_speed_mps * dt + options_.slack_m;
  if (std::abs(dl) > limit || std::abs(dr) > limit) {
    ++discontinuities_;
    return OdometryStep::kDiscontinuity;
  }
  const double ds = 0.5 * (dl + dr);
  const double dtheta = (dr - dl) / options_.track_width_m;
  Pose2 step;
  if (std::abs(dtheta) < 1e-9) {
    step = Pose2{ds, 0.0, dtheta};
  } else {
    const double radius = ds / dtheta;
    step = Pose2{radius * std::sin(dtheta), radius * (1.0 - std::cos(dtheta)), dtheta};
  }
  sample_.pose = Compose(sample_.pose, step);
  return OdometryStep::kIntegrated;
}

}  // namespace atlas::agilex
