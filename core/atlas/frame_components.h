#pragma once
// Connected parts of the atlas graph, kept incrementally (union-find with path halving and
// union by size): O(alpha(n)) per frame added, edge added or query.
//
// The atlas is connected while it grows by Genesis and map-matching. It falls apart only when a
// saved atlas is resumed in a new, unconnected frame (Atlas::ResumeInNewFrame): the robot does
// not know where it is in the old frames, and the Dijkstra projection from its frame cannot
// reach them. Map-matching then also tries frames of other parts, without a prior
// (Section III-D; Condition 2 without a prior: every repetition makes a match ambiguous), and
// this structure tells which frames those are.

#include <vector>

#include "core/atlas/atlas_graph.h"

namespace atlas {

class FrameComponents {
 public:
  // Frames 0..n-1, joined by the graph's edges. O(frames + edges).
  void Rebuild(const AtlasGraph& graph);
  // The next frame id (must be Count()), alone in its part.
  void AddFrame();
  // Joins the parts of a and b (an edge was added).
  void Join(FrameId a, FrameId b);
  // A representative of f's part: equal for frames of one part.
  FrameId Root(FrameId f);
  bool Connected(FrameId a, FrameId b) { return Root(a) == Root(b); }
  // Frames in f's part.
  int Size(FrameId f) { return size_[Root(f)]; }
  int Count() const { return static_cast<int>(parent_.size()); }

 private:
  std::vector<FrameId> parent_;
  std::vector<int> size_;
};

}  // namespace atlas
