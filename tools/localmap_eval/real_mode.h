#pragma once
// atlas-localmap-eval real: mit-csail, one local map per stretch of M metres of travel (no
// Genesis), scored on the relations whose two poses lie in one stretch, against dead reckoning
// on the same ones; optionally draws one local map over its scans. With a laser time offset the
// filter's odometry is interpolated at each scan's stamp + S (step_loop.h). Dead reckoning is
// the log's odometry at the relation stamps (and, with an offset, also at stamp + S).

#include "tools/cli/tool_modes.h"

namespace atlas::localmap_eval {

cli::ToolMode RealMode();

}  // namespace atlas::localmap_eval
