#pragma once
// The filter's odometry model of the simulated base (drivers/sim WheelOdometryModel): the wheel
// noise as simulated and no other noise; the base's calibration errors (systematic, the same
// every step) enter with their sizes as the standard deviations of the filter's calibration
// model (OdometryNoiseOptions).

#include "core/localmap/localmap_options.h"
#include "sim/wheel_odometry_model.h"

namespace atlas::mc {

OdometryNoiseOptions SimulatedBaseOdometry(const WheelOdometryNoiseOptions& wheel);

}  // namespace atlas::mc
