#pragma once
// False loop closures against a reference trajectory (the corrected logs): every edge made
// by map-matching (paper, Section III-D) is compared with the reference transform between the
// origins of its two frames.
//
// A frame's origin is the robot's pose at the scan of the step that created it (Genesis,
// Section III-C: "the current robot pose defines the origin of a new frame"; frame 0: the first
// scan), so the true pose of frame b in frame a is Between(ref(origin a), ref(origin b)).
// The edge's current estimate is compared (an edge refined by covariance intersection after it
// was made is judged as it ended up). Error e = (dx, dy, wrap(dtheta)) of the estimate minus the
// reference, in frame a's coordinates, where the edge's covariance lives.
// Tests, both reported:
//  - chi-square, 3 dof: e^T Sigma^-1 e > 14.16 (P = 0.9973, the two-sided 3-sigma probability
//    of one dimension) -- the count called "false closures";
//  - per axis: any |e_i| > 3 sqrt(Sigma_ii).
// The reference's own error (GMapping, ~5 cm) is not in Sigma: an edge whose covariance is far
// below that may be flagged while close to the truth, so gross errors are counted as well.

#include <optional>
#include <string>
#include <vector>

#include "core/atlas/atlas_graph.h"

namespace atlas::replay {

struct ClosureCheckOptions {
  double chi2_threshold = 14.156;  // 3 dof, P = 0.9973
  double axis_sigmas = 3.0;
  double gross_translation_m = 0.5;
  double gross_rotation_deg = 5.0;
  std::string Validate() const;
};

struct ClosureVerdict {
  FrameId a = kNoFrame, b = kNoFrame;
  EdgeKind kind = EdgeKind::kMapMatch;  // current kind (map-match, or refined later)
  Pose2 estimate;                       // pose of b in a, the edge
  Pose2 reference;                      // pose of b in a, from the reference
  Vec3 error = Vec3::Zero();            // estimate - reference (theta wrapped)
  double d2 = 0.0;                      // Mahalanobis distance squared, 3 dof
  double worst_axis_sigmas = 0.0;       // max_i |e_i| / sigma_i
  bool false_chi2 = false, false_axis = false, gross = false;
};

struct ClosureReport {
  std::vector<ClosureVerdict> edges;
  int map_match_edges = 0;  // edges first made by map-matching
  int unreferenced = 0;     // of those, with a frame whose origin has no reference pose
  int false_chi2 = 0, false_axis = 0, gross = 0;
};

// One edge (its current estimate) against the reference poses of its frames' origins.
ClosureVerdict CheckClosure(const AtlasEdge& edge, const Pose2& reference_a,
                            const Pose2& reference_b, const ClosureCheckOptions& options);

// `origin_reference[f]` is the reference pose of frame f's origin (nullopt when unknown).
ClosureReport CheckClosures(const AtlasGraph& graph,
                            const std::vector<std::optional<Pose2>>& origin_reference,
                            const ClosureCheckOptions& options);

// closures.tsv: one row per checked edge (docs/formats.md).
std::string FormatClosures(const ClosureReport& report);

}  // namespace atlas::replay
