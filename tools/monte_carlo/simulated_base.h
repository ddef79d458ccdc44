#pragma once
// The filter's odometry model of the simulated base (drivers/sim WheelOdometryModel): the wheel
// noise as simulated and no other noise; the base's calibration errors (systematic, the same
// every step) enter with their sizes as the standard deviations of the filter's calibration
// model (OdometryNoiseOptions).

#include "core/localmap/localmap_options.h"
#include "sim/wheel_odometry_model.h"

namespace atlas::mc {

OdometryNoiseOptions SimulatedBaseOdometry(const WheelOdometryNoiseOptions& wheel);

// The line extraction for the simulator's laser (range sigma `range_sigma`, metres): its walls
// are straight and its noise is the model's, so no wall noise and no floors on the fitted
// lines (core/localmap's defaults are those of a real building's walls).
void UseSimulatedWalls(double range_sigma, LineExtractionOptions* o);

}  // namespace atlas::mc
