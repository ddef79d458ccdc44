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
  if (!(max_gap_s > 0.0) || !std::isfinite(max_gap_s))
    return "max_gap_s must be a positive number of seconds (a few 20 ms frame periods)";
  return {};
}

const char* ToString(DiscontinuityCause c) {
  switch (c) {
    case DiscontinuityCause::kNone:
      return "none";
    case DiscontinuityCause::kImplausibleChange:
      return "counters jumped";
    case DiscontinuityCause::kGap:
      return "gap between frames";
    case DiscontinuityCause::kRereferenced:
      return "reconnected";
  }
  return "?";
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
  const bool rereference = rereference_;
  last_ = counters;
  last_stamp_ = stamp;
  have_reference_ = true;
  rereference_ = false;
  sample_.stamp = stamp;
  if (!had_reference) return OdometryStep::kFirst;
  auto discontinuity = [&](DiscontinuityCause cause) {
    ++discontinuities_;
    last_cause_ = cause;
    return cause == DiscontinuityCause::kImplausibleChange ? OdometryStep::kDiscontinuity
                                                           : OdometryStep::kRereferenced;
  };
  if (rereference) return discontinuity(DiscontinuityCause::kRereferenced);

  const double dt = std::max(0.0, ToSeconds(stamp - previous_stamp));
  if (dt > options_.max_gap_s) return discontinuity(DiscontinuityCause::kGap);
  const double dl = (static_cast<int64_t>(counters.left_mm) - previous.left_mm) * 1e-3;
  const double dr = (static_cast<int64_t>(counters.right_mm) - previous.right_mm) * 1e-3;
  // A frame covers at least the base's own period, however close it arrived to the last one.
  const double limit = options_.max_speed_mps * std::max(dt, kFramePeriodS) + options_.slack_m;
  if (std::abs(dl) > limit || std::abs(dr) > limit)
    return discontinuity(DiscontinuityCause::kImplausibleChange);
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
  sample_.left_m = counters.left_mm * 1e-3;
  sample_.right_m = counters.right_mm * 1e-3;
  return OdometryStep::kIntegrated;
}

}  // namespace atlas::agilex
