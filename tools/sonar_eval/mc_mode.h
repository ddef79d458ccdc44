#pragma once
// atlas-sonar-eval mc: the one-map consistency check in the simulated corridor. On each seeded
// run a sonar-only and a laser-only SonarLocalMap process the same odometry; prints the robot
// NEES (3 dof) averaged over the runs against its 95 % band, the NEES of each sonar line at its
// initialisation against the nearest true wall (2 dof, and 5 dof with the robot pose), and
// relative-pose errors over pairs 5, 30 and 90 s apart for sonar, laser and dead reckoning.

#include "tools/cli/tool_modes.h"

namespace atlas::sonar_eval {

cli::ToolMode McMode();

}  // namespace atlas::sonar_eval
