#include "tools/replay/replay_refiner.h"

#include <chrono>

namespace atlas::replay {

Refiner MakeRefiner(const refine::RefineOptions& options) {
  return [options](const AtlasGraph& graph, ReplaySummary* sum) {
    const auto r0 = std::chrono::steady_clock::now();
    refine::RefineResult refined = refine::RefineGlobal(graph, options);
    sum->refine_seconds =
        std::chrono::duration<double>(std::chrono::steady_clock::now() - r0).count();
    sum->refine_status = refine::ToString(refined.status);
    sum->refined_frames = refined.frames;
    sum->refine_constraints = refined.edges;
    sum->refine_initial_cost = refined.initial_cost;
    sum->refine_final_cost = refined.final_cost;
    sum->refine_iterations = refined.iterations;
    sum->refine_unreached_frames = refined.unreached;
    sum->refine_skipped_edges = refined.skipped_edges;
    return std::move(refined.refined);
  };
}

}  // namespace atlas::replay
