#pragma once
// Relative poses read from the Atlas's own output, composed as the paper does (Section III-A):
// each trajectory pose lives in its own map-frame; the pose at t2 in the frame of the pose at
// t1 is, when both lie in one frame, Between(P1, P2); when the frames differ, P2 is carried into
// P1's frame along the Dijkstra path (minimum rho = det of the composed covariance, eq. 2-3)
// between the two frames in the given graph (DijkstraProjection rooted at P1's frame), then
// Between(P1, T (+) P2). No global arrangement is involved. Pure, no I/O.

#include <cstdint>
#include <map>
#include <optional>
#include <span>
#include <string>
#include <vector>

#include "core/atlas/atlas_graph.h"
#include "core/atlas/dijkstra_projection.h"
#include "core/eval/relations_metric.h"
#include "core/eval/timed_trajectory.h"

namespace atlas::eval {

// A trajectory row of atlas-replay's trajectory.tsv: the pose in map-frame `frame`.
struct FramePose {
  Time stamp{};
  FrameId frame = kNoFrame;
  Pose2 pose;
};

// An edge row of graph.tsv: the pose of `to` in `from`, with covariance.
struct EdgeRow {
  FrameId from = kNoFrame;
  FrameId to = kNoFrame;
  UncertainPose to_in_from;
  EdgeKind kind = EdgeKind::kGenesis;
};

// Builds a graph (frames 0 .. frame_count-1 without maps, degree bounded by the largest degree
// among the edges) from edge rows.
// Returns an error ("edge <index>: <why>") for an edge naming an unknown frame, a self-loop or a
// second edge between the same two frames.
std::string BuildGraphFromEdges(int frame_count, std::span<const EdgeRow> edges, AtlasGraph* out);

// How the atlas joins a relation's two poses: the path its composition follows. A loop is
// closed where the robot returns (Fig. 7) when the return's poses share a frame, lie in
// neighbouring frames, or are joined through a map-match edge (III-D); otherwise the relation
// follows a chain of two or more Genesis (or refined) edges, and carries their drift.
enum class FrameJoin { kSameFrame, kNeighbours, kThroughMapMatch, kChain };
const char* FrameJoinName(FrameJoin join);  // "same", "neighbours", "map-match", "chain"

struct CompositionCounts {
  int64_t same_frame = 0;         // both poses in one frame
  int64_t cross_frame = 0;        // composed along a Dijkstra path: the three below
  int64_t neighbours = 0;         // a path of one edge, not made by map-matching
  int64_t through_map_match = 0;  // a path with an edge made by map-matching (kind kMapMatch)
  int64_t chain = 0;              // two or more edges, none made by map-matching
  int64_t unconnected = 0;        // frames not connected in the graph (no relative pose)
  int64_t unmatched = 0;          // a stamp without a trajectory pose
};

class DijkstraComposedPoses {
 public:
  // `graph` must outlive this object and contain every frame the trajectory names.
  DijkstraComposedPoses(std::vector<FramePose> trajectory, const AtlasGraph& graph,
                        Duration tolerance = kDefaultMatchTolerance);

  // The estimated pose at t2 in the frame of the estimated pose at t1, counted in Counts().
  // With `join`, also how the two poses are joined (set only when a pose is returned).
  std::optional<Pose2> operator()(Time t1, Time t2, FrameJoin* join = nullptr);
  const CompositionCounts& Counts() const { return counts_; }

 private:
  const Projection& ProjectionFrom(FrameId source);

  TimedTrajectory poses_;       // sorted by stamp
  std::vector<FrameId> frame_;  // aligned with poses_
  const AtlasGraph& graph_;
  Duration tolerance_;
  DijkstraWorkspace workspace_;
  std::map<FrameId, Projection> projections_;  // memoised per source frame
  CompositionCounts counts_;
};

}  // namespace atlas::eval
