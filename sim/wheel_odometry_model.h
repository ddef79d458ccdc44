#pragma once
// A seeded differential-drive wheel-odometry error model.
//
// From consecutive true poses it derives the distances the left and right wheels rolled, applies
// the errors of a real base, and integrates the erroneous wheel distances with the *nominal*
// track width into a cumulative odometry pose, as a robot's firmware does:
//
//   true wheels   d_l = s - dtheta * b_true / 2,   d_r = s + dtheta * b_true / 2
//                 (s = arc length of the step, b_true = track_width_m * (1 + track_width_error))
//   measured      d_l' = d_l (1 + left_scale_error)  + N(0, wheel_noise_per_m * |d_l|)
//                 d_r' = d_r (1 + right_scale_error) + N(0, wheel_noise_per_m * |d_r|)
//   integrated    s' = (d_l' + d_r') / 2,   dtheta' = (d_r' - d_l') / track_width_m
//
// Random noise therefore has a variance proportional to the distance each wheel rolled
// (independent increments), and the systematic errors are the two classic ones of Borenstein's
// UMBmark: unequal wheel radii (heading drift on a straight line of (right - left) / b radians
// per metre) and an uncalibrated track width (a turn of phi is reported as phi (1 + error)).
//
// Each step is treated as a circular arc. Motion of the truth that no arc explains (sideways
// slip in a reference trajectory) is passed through unchanged in the robot frame, so that with
// every error zero the odometry reproduces the truth exactly. The odometry frame starts at the
// first true pose. Used by the simulator and to synthesise odometry for logs whose reference
// trajectory is known (the corrected logs). Pure computation: no I/O.

#include <cstdint>
#include <random>
#include <string>
#include <string_view>

#include "core/common/sensor_types.h"

namespace atlas {

struct WheelOdometryNoiseOptions {
  // Nominal distance between the wheels' contact points (P3-DX: 0.33 m, B21: ~0.5 m).
  double track_width_m = 0.4;
  // Variance of each wheel's distance error per metre that wheel rolled, in m^2/m
  // (i.e. sigma = sqrt(wheel_noise_per_m) metres after one metre). Default: 2.2 mm after 1 m.
  double wheel_noise_per_m = 5e-6;
  // Relative wheel-radius errors (0.001 = the wheel reports 0.1 % more than it rolled).
  // Defaults: a UMBmark-calibrated base (uncalibrated ones are ~5-10 times worse): heading
  // drift (right - left) / b = 1 mrad (0.06 deg) per metre on a straight line.
  double left_scale_error = 0.0002;
  double right_scale_error = -0.0002;
  // Relative error of the nominal track width: the true track width is
  // track_width_m * (1 + track_width_error).
  double track_width_error = 0.002;
  // Variance of a distance error common to both wheels (slip, an uneven floor), m^2 per metre
  // travelled: it changes the distance but not the heading.
  double common_noise_per_m = 0.0;

  // Empty when valid, else what is wrong.
  std::string Validate() const;
};

// Named noise levels, for the tools' --odometry-noise:
//   default    the defaults above (a calibrated base)
//   realistic  a real base: distance random 2 % per metre (sigma after 1 m straight), distance
//              scale +1 %, turns +1 % (the wheels' scale; the track width is right), heading
//              drift 0.1 deg per metre on a straight line; the random heading noise stays
//              the default's (wheel_noise_per_m).
// Sets every field but track_width_m (the drift is made for the track width already set).
// False if `level` names no level.
bool SetOdometryNoiseLevel(std::string_view level, WheelOdometryNoiseOptions* options);
// The tools' help for --odometry-noise, with mit-csail's own B21 odometry beside the levels.
extern const char* const kOdometryNoiseHelp;

class WheelOdometryModel {
 public:
  // `options` must be valid (Validate() empty).
  WheelOdometryModel(const WheelOdometryNoiseOptions& options, uint64_t seed);

  // Feeds the next true pose (stamps non-decreasing) and returns the odometry pose at its
  // stamp. The first call returns the start pose (the first true pose).
  OdometrySample Step(const TruthSample& truth);

 private:
  WheelOdometryNoiseOptions options_;
  std::mt19937_64 rng_;
  std::normal_distribution<double> unit_normal_{0.0, 1.0};
  bool started_ = false;
  Pose2 last_truth_;
  Pose2 odometry_;
};

}  // namespace atlas
