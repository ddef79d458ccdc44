#pragma once
// The options of wheel odometry synthesised by sim/wheel_odometry_model.h, one group shared by
// atlas-sim and by atlas-replay and atlas-carmen on corrected logs: the same names, and the
// defaults of WheelOdometryNoiseOptions, defined there once.

#include <string>

#include "sim/wheel_odometry_model.h"
#include "tools/cli/command_line.h"

namespace atlas::cli {

// Adds, in the help group `group`: --track-width M, --odometry-noise LEVEL, --wheel-noise V,
// --left-scale-error E, --right-scale-error E, --track-width-error E, each into `noise`. They
// are applied in this order whatever their order on the command line: the track width, then
// the level (SetOdometryNoiseLevel, which keeps the track width), then the single errors, which
// override the level's.
void AddOdometryNoiseOptions(CLI::App& app, const std::string& group,
                             WheelOdometryNoiseOptions* noise);

}  // namespace atlas::cli
