#pragma once
// atlas-localmap-eval mc: Monte Carlo consistency of the line EKF (core/localmap) in the
// simulated corridor (tools/monte_carlo/corridor.h): the average NEES of the robot pose and of
// the features per step against the 95 % chi-square band, and the simulator's odometry errors
// whitened with the filter's Q.

#include "tools/cli/tool_modes.h"

namespace atlas::localmap_eval {

cli::ToolMode McMode();

}  // namespace atlas::localmap_eval
