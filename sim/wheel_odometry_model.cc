#include "sim/wheel_odometry_model.h"

#include <cmath>
#include <numbers>

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
  if (!(common_noise_per_m >= 0.0 && common_noise_per_m < 1.0))
    return "common_noise_per_m must be in [0, 1) m^2 per metre";
  return "";
}

bool SetOdometryNoiseLevel(std::string_view level, WheelOdometryNoiseOptions* options) {
  WheelOdometryNoiseOptions o;
  o.track_width_m = options->track_width_m;
  if (level == "realistic") {
    constexpr double kScale = 0.01, kRandomPerMetre = 0.02;
    constexpr double kDriftRadPerMetre = 0.1 * std::numbers::pi / 180.0;
    // Drift on a straight line is (right - left) / track width; turns scale as the wheels do.
    o.left_scale_error = kScale - 0.5 * kDriftRadPerMetre * o.track_width_m;
    o.right_scale_error = kScale + 0.5 * kDriftRadPerMetre * o.track_width_m;
    o.track_width_error = 0.0;
    // The wheels' own noise adds wheel_noise_per_m / 2 to the distance's variance.
    o.common_noise_per_m = kRandomPerMetre * kRandomPerMetre - 0.5 * o.wheel_noise_per_m;
  } else if (level != "default") {
    return false;
  }
  *options = o;
  return true;
}

const char* const kOdometryNoiseHelp =
    "\nOdometry noise levels (--odometry-noise):\n"
    "  default    a calibrated base: wheel radii 0.02 %, track width 0.2 % off, 2.2 mm of\n"
    "             random error per metre each wheel rolled\n"
    "  realistic  a real base: distance random 2 % per metre, distance scale and turns +1 %,\n"
    "             heading drift 0.1 deg per metre on a straight line\n"
    "  Median error per metre over relations 0.5-3 m long: mit-csail's own B21 odometry\n"
    "  against its relations 9.4 % and 3.3 deg (341 relations; 2.9 deg with the odometry\n"
    "  taken 0.1 s before the scan stamps); the realistic level 1.7 % and 0.35 deg, the\n"
    "  default 0.5 % and 0.27 deg (a simulated 0.5 km office run, 837 relations). Real\n"
    "  bases can be worse than the realistic level.\n"
    "  A level sets the wheel-noise options; --left-scale-error, --right-scale-error,\n"
    "  --track-width-error and --wheel-noise override it wherever they stand.\n";

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

  double arc_meas = 0.5 * (dl_meas + dr_meas);
  if (options_.common_noise_per_m > 0.0)
    arc_meas += std::sqrt(options_.common_noise_per_m * std::abs(arc)) * unit_normal_(rng_);
  const double dth_meas = (dr_meas - dl_meas) / options_.track_width_m;
  const double chord_meas = arc_meas * ChordOverArc(dth_meas);
  const double c2 = std::cos(0.5 * dth_meas), s2 = std::sin(0.5 * dth_meas);
  const Pose2 rel_meas{chord_meas * c2 - sideways * s2, chord_meas * s2 + sideways * c2,
                       WrapAngle(dth_meas)};
  odometry_ = Compose(odometry_, rel_meas);
  return OdometrySample{truth.stamp, odometry_};
}

}  // namespace atlas
