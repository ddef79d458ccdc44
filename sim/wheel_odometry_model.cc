#include "sim/wheel_odometry_model.h"

#include <cmath>

namespace atlas {
namespace {

// sin(x/2) / (x/2), continuous at 0.
double ChordOverArc(double x) {
  const double h = 0.5 * x;
  return std::abs(h) < 1e-6 ? 1.0 - h * h / 6.0 : std::sin(h) / h;
}

}  // namespace

std::string WheelOdometryNoiseOptions::Validate() const {
  if (!(track_width_m > 0.0 && track_width_m < 10.0))
    return "track_width_m must be in (0, 10) metres";
  if (!(wheel_noise_per_m >= 0.0 && wheel_noise_per_m < 1.0))
    return "wheel_noise_per_m must be in [0, 1) m^2 per metre";
  if (!(std::abs(left_scale_error) < 0.5) || !(std::abs(right_scale_error) < 0.5))
    return "left_scale_error and right_scale_error must be in (-0.5, 0.5)";
  if (!(std::abs(track_width_error) < 0.5)) return "track_width_error must be in (-0.5, 0.5)";
  return "";
}

WheelOdometryModel::WheelOdometryModel(const WheelOdometryNoiseOptions& options, uint64_t seed)
    : options_(options), rng_(seed) {}

OdometrySample WheelOdometryModel::Step(const TruthSample& truth) {
  if (!started_) {
    started_ = true;
    last_truth_ = truth.pose;
    odometry_ = truth.pose;
    return OdometrySample{truth.stamp, odometry_};
  }
  const Pose2 rel = Between(last_truth_, truth.pose);
  last_truth_ = truth.pose;

  // Decompose into an arc (chord along heading dtheta/2) and an unexplained sideways residual.
  const double dth = rel.theta;
  const double ch = std::cos(0.5 * dth), sh = std::sin(0.5 * dth);
  const double chord = rel.x * ch + rel.y * sh;
  const double sideways = -rel.x * sh + rel.y * ch;
  const double arc = chord / ChordOverArc(dth);

  const double b_true = options_.track_width_m * (1.0 + options_.track_width_error);
  const double dl = arc - 0.5 * dth * b_true;
  const double dr = arc + 0.5 * dth * b_true;
  const double k = options_.wheel_noise_per_m;
  const double dl_meas = dl * (1.0 + options_.left_scale_error) +
                         (k > 0.0 ? std::sqrt(k * std::abs(dl)) * unit_normal_(rng_) : 0.0);
  const double dr_meas = dr * (1.0 + options_.right_scale_error) +
                         (k > 0.0 ? std::sqrt(k * std::abs(dr)) * unit_normal_(rng_) : 0.0);

  const double arc_meas = 0.5 * (dl_meas + dr_meas);
  const double dth_meas = (dr_meas - dl_meas) / options_.track_width_m;
  const double chord_meas = arc_meas * ChordOverArc(dth_meas);
  const double c2 = std::cos(0.5 * dth_meas), s2 = std::sin(0.5 * dth_meas);
  const Pose2 rel_meas{chord_meas * c2 - sideways * s2, chord_meas * s2 + sideways * c2,
                       WrapAngle(dth_meas)};
  odometry_ = Compose(odometry_, rel_meas);
  return OdometrySample{truth.stamp, odometry_};
}

}  // namespace atlas
