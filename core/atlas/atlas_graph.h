#pragma once
// The atlas graph (paper, Section II): vertices are map-frames, each owning a local map in its
// own coordinates; edges are undirected uncertain transforms between adjacent frames.
//
// Contract:
// - Frame ids are dense, 0, 1, 2, ... in order of Genesis, and never reused (Fig. 7 plots them).
// - An edge stores the pose of frame `b` in frame `a` with its covariance; read in the reverse
//   direction it yields the inverse transform with covariance J(-) Sigma J(-)^T (Section II:
//   "the reverse direction of an edge contains the inverse transformation").
// - Every edge records how it was made: Genesis (III-C), map-matching (III-D) or refined by
//   covariance intersection (III-F).
// - Memory per frame is bounded: a frame has at most `max_degree` edges (AddEdge returns
//   kDegreeFull beyond that) and its map is bounded by the map capacity.
// - Look-ups are O(degree); nothing here iterates over all frames except the explicit
//   whole-graph accessors used by output and offline tools.

#include <cstdint>
#include <memory>
#include <vector>

#include "core/atlas/frame_points.h"
#include "core/geometry/se2.h"
#include "core/localmap/local_map.h"

namespace atlas {

using FrameId = int32_t;
inline constexpr FrameId kNoFrame = -1;

enum class EdgeKind : uint8_t { kGenesis = 0, kMapMatch = 1, kRefined = 2 };
const char* EdgeKindName(EdgeKind kind);

struct AtlasEdge {
  FrameId a = kNoFrame;
  FrameId b = kNoFrame;
  UncertainPose b_in_a;                // pose of frame b in frame a, covariance over (x, y, theta)
  EdgeKind kind = EdgeKind::kGenesis;  // current estimate's provenance
  EdgeKind origin = EdgeKind::kGenesis;  // how the edge was first made
  int64_t made_step = 0;                 // step at which the edge was made
  int64_t refined_step = -1;             // last covariance-intersection update, -1 if never
  int refinements = 0;
};

struct MapFrame {
  FrameId id = kNoFrame;
  std::unique_ptr<LocalMap> map;
  FramePoints points;  // the laser endpoints its map was built from (frame_points.h), if kept
  std::vector<int32_t> edges;  // indices into AtlasGraph::Edges(), at most max_degree
  int64_t created_step = 0;
  // Bookkeeping the step loop keeps per frame (bounded, O(1) per frame).
  int64_t seed_cooldown_until = -1;  // no juvenile is seeded here before this step
  int retirements = 0;               // how often a mature hypothesis here was retired
  // Changes whenever the map may have changed (AtlasGraph::AddFrame, MutableMap, ReplaceMap),
  // to a value no frame of any graph in this process had before: a saver that remembers the
  // revisions it wrote writes only the maps that changed since. Not part of the atlas image.
  uint64_t map_revision = 0;
};

enum class AddEdgeResult { kAdded, kDegreeFull, kSameFrame, kAlreadyAdjacent, kBadFrame };

class AtlasGraph {
 public:
  explicit AtlasGraph(int max_degree = 16) : max_degree_(max_degree) {}
  AtlasGraph(AtlasGraph&&) = default;
  AtlasGraph& operator=(AtlasGraph&&) = default;

  // Adds a frame owning `map` and returns its id.
  FrameId AddFrame(std::unique_ptr<LocalMap> map, int64_t step = 0);
  AddEdgeResult AddEdge(FrameId a, FrameId b, const UncertainPose& b_in_a, EdgeKind kind,
                        int64_t step = 0);

  int FrameCount() const { return static_cast<int>(frames_.size()); }
  int EdgeCount() const { return static_cast<int>(edges_.size()); }
  int max_degree() const { return max_degree_; }
  bool HasFrame(FrameId id) const { return id >= 0 && id < FrameCount(); }
  const MapFrame& Frame(FrameId id) const { return frames_[id]; }
  // Changing a frame's map goes through MutableMap or ReplaceMap, which change its
  // map_revision; MutableFrame is for the rest of the frame.
  MapFrame& MutableFrame(FrameId id) { return frames_[id]; }
  LocalMap& MutableMap(FrameId id);
  void ReplaceMap(FrameId id, std::unique_ptr<LocalMap> map);
  const std::vector<AtlasEdge>& Edges() const { return edges_; }
  const AtlasEdge& Edge(int index) const { return edges_[index]; }

  // The index of the edge joining a and b, or -1. O(degree of a).
  int FindEdge(FrameId a, FrameId b) const;
  // The other end of edge `index` seen from `from`.
  FrameId OtherEnd(int index, FrameId from) const;
  // The pose of `to` in `from` along edge `index` (inverse with propagated covariance when the
  // edge is stored the other way round).
  UncertainPose Transform(int index, FrameId from) const;
  // Replaces the transform of edge `index`, given as the pose of `to` in `from`.
  void SetTransform(int index, FrameId from, const UncertainPose& to_in_from, EdgeKind kind,
                    int64_t step);
  // For Atlas::Deserialize: marks edge `index` as refined `refinements` times, last at
  // `refined_step`, keeping its stored transform (O(1), whatever the count).
  void RestoreRefinements(int index, int refinements, int64_t refined_step);

 private:
  int max_degree_;
  std::vector<MapFrame> frames_;
  std::vector<AtlasEdge> edges_;
};

}  // namespace atlas
