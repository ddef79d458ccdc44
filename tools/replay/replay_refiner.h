#pragma once
// The replay's global refinement (ReplayOptions::refine): tools/refine/global_refinement.h over
// the finished atlas graph, its figures into the replay summary.

#include "replay/replay_run.h"
#include "tools/refine/global_refinement.h"

namespace atlas::replay {

Refiner MakeRefiner(const refine::RefineOptions& options);

}  // namespace atlas::replay
