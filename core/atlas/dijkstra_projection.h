#pragma once
// Uncertainty projection and the Dijkstra projection (paper, Section III-A).
//
// Paths are composed with eq. 2 (Compose of UncertainPose) and the length of a path is
// rho = det(Sigma of the composed transform), eq. 3. Since every SE(2) composition Jacobian has
// determinant 1 and det(A + B) >= det(A) for positive semi-definite A, B, rho never decreases
// along a path, so Dijkstra's greedy settling is exact for this metric.
//
// The projection from a source frame is a tree: every reached frame gets a parent and the pose
// of the frame in the source frame (composed along the tree path) with its covariance.
//
// Two uses, two costs:
// - Bounded (the step loop): settle at most `max_frames` frames and stop beyond `max_rho`. The
//   heap then holds at most max_frames * max_degree entries, so the cost is independent of the
//   number of frames in the atlas.
// - Full (output, offline tools): max_frames = unlimited; O(E log V).
// A DijkstraWorkspace keeps per-frame scratch that is reused between calls (grown only when
// frames are added), so a bounded projection allocates nothing once warm.

#include <Eigen/LU>
#include <limits>
#include <vector>

#include "core/atlas/atlas_graph.h"

namespace atlas {

struct ProjectionLimits {
  int max_frames = std::numeric_limits<int>::max();
  double max_rho = std::numeric_limits<double>::infinity();
};

struct ProjectedFrame {
  FrameId frame = kNoFrame;
  FrameId parent = kNoFrame;  // kNoFrame for the source
  int parent_edge = -1;
  int hops = 0;
  UncertainPose pose;  // the pose of `frame` in the source frame
  double rho = 0.0;    // det(pose.cov), eq. 3
};

struct Projection {
  FrameId source = kNoFrame;
  // Settled frames in order of increasing rho; entries[0] is the source.
  std::vector<ProjectedFrame> entries;
  // True when the limits stopped the search before every reachable frame was settled.
  bool truncated = false;
  // The entry for `frame`, or nullptr if it was not reached. O(entries).
  const ProjectedFrame* Find(FrameId frame) const;
};

class DijkstraWorkspace {
 public:
  // Fills `out` with the projection of `graph` from `source`. Returns false (and leaves `out`
  // empty) when `source` is not a frame of the graph.
  bool Project(const AtlasGraph& graph, FrameId source, const ProjectionLimits& limits,
               Projection* out);

 private:
  struct HeapItem {
    double rho;
    int slot;
  };
  std::vector<uint32_t> visit_generation_;  // per frame
  std::vector<int32_t> slot_of_frame_;      // per frame: index into candidates_
  std::vector<ProjectedFrame> candidates_;
  std::vector<uint8_t> settled_;
  std::vector<HeapItem> heap_;
  uint32_t generation_ = 0;
};

// Convenience: a one-off projection (allocates its own workspace).
Projection DijkstraProjection(const AtlasGraph& graph, FrameId source,
                              const ProjectionLimits& limits = {});

}  // namespace atlas
