#pragma once
// atlas-sonar-eval fig9: a picture like the paper's Fig. 9 (Section IV): the returns (arcs),
// vantage points and lines of the first K sonar feature initialisations (map frame, estimated
// poses) over the true walls, in the corridor of the mc mode.

#include "tools/cli/tool_modes.h"

namespace atlas::sonar_eval {

cli::ToolMode Fig9Mode();

}  // namespace atlas::sonar_eval
