#pragma once
// Offline global refinement of an atlas graph (paper, Section I-A: the Atlas does not constrain
// the composition of edges around a loop to the identity, "this constraint can be applied
// off-line to refine the global arrangement of the multiple coordinate frames").
//
// Every frame f connected to frame 0 gets a global pose X_f (frame 0 fixed at the origin). Each
// edge (a, b) with estimate T_ab (pose of b in a) and covariance S_ab is a relative SE(2)
// constraint with residual
//   r_ab = S_ab^(-1/2) [ R(theta_a)^T (t_b - t_a) - t_ab ;  wrap(theta_b - theta_a - theta_ab) ]
// (the error expressed in frame a, where S_ab lives), and the refined arrangement minimises
// sum |r_ab|^2 (Ceres, sparse Cholesky Levenberg-Marquardt). The initial arrangement is the
// Dijkstra projection from frame 0 (Section III-A). A covariance is floored at `min_variance` on
// its diagonal (a Genesis edge made right after an update can carry a near-singular
// covariance); an edge whose covariance is then still not usable (not finite, a negative
// variance, not positive definite) is left out and counted in `skipped_edges`. Frames not
// connected to frame 0 through the usable edges are left out and counted in `unreached`.
//
// Never in the step loop: its cost grows with the whole graph.

#include <optional>
#include <string>
#include <vector>

#include "core/atlas/atlas_graph.h"

namespace atlas::refine {

struct RefineOptions {
  int max_iterations = 100;
  double function_tolerance = 1e-12;
  double min_variance = 1e-10;
  std::string Validate() const;  // empty when valid
};

enum class RefineStatus { kConverged, kNoConvergence, kNoFrames, kFailed };
const char* ToString(RefineStatus s);

struct RefineResult {
  RefineStatus status = RefineStatus::kNoFrames;
  // Per frame id: the global pose (frame 0 = identity), nullopt if not connected to frame 0.
  std::vector<std::optional<Pose2>> initial;  // the Dijkstra projection from frame 0
  std::vector<std::optional<Pose2>> refined;
  int frames = 0;                               // frames placed
  int unreached = 0;                            // frames not connected to frame 0 (left out)
  int edges = 0;                                // constraints used
  int skipped_edges = 0;                        // edges left out: covariance not usable
  double initial_cost = 0.0, final_cost = 0.0;  // 1/2 sum |r|^2
  int iterations = 0;
  std::string message;  // the solver's report line
};

RefineResult RefineGlobal(const AtlasGraph& graph, const RefineOptions& options);

}  // namespace atlas::refine
