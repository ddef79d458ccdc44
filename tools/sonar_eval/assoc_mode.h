#pragma once
// atlas-sonar-eval assoc: one sonar-only local map (no atlas) through a world (world_option.h).
// Every return the map applied to a feature is checked against the wall the simulator echoed
// it from (in-cone and edge-of-cone pairings: the true wall's line, another line, or no wall:
// multipath); the first N wrong pairings are listed; NEES every 10 s.

#include "tools/cli/tool_modes.h"

namespace atlas::sonar_eval {

cli::ToolMode AssocMode();

}  // namespace atlas::sonar_eval
