#pragma once
// Wheel odometry synthesised from a log's reference trajectory (the corrected logs):
// every reference pose is fed, in order, to the simulator's WheelOdometryModel
// (sim/wheel_odometry_model.h: noise proportional to distance travelled, wheel-radius
// and track-width errors, seeded), and its output becomes an OdometrySample at the same stamp.
// The log's scans are kept; the synthesised odometry is merged in time order, a sample before
// a scan of the same stamp.

#include <cstdint>
#include <vector>

#include "logs/carmen/carmen_log.h"
#include "sim/wheel_odometry_model.h"

namespace atlas::carmen {

// `log` must have been read with reference_trajectory set; `noise` must be valid. Returns the
// log's events with one synthesised odometry event per reference pose (the pose's line,
// message "ODOM"), time-ordered.
std::vector<CarmenEvent> EventsWithSynthesizedOdometry(const CarmenLog& log,
                                                       const WheelOdometryNoiseOptions& noise,
                                                       uint64_t seed);

}  // namespace atlas::carmen
