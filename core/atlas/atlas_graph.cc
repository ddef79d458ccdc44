#include "core/atlas/atlas_graph.h"

#include <atomic>
#include <cassert>

namespace atlas {
namespace {

uint64_t NewMapRevision() {
  static std::atomic<uint64_t> last{0};
  return last.fetch_add(1, std::memory_order_relaxed) + 1;
}

}  // namespace

const char* EdgeKindName(EdgeKind kind) {
  switch (kind) {
    case EdgeKind::kGenesis:
      return "genesis";
    case EdgeKind::kMapMatch:
      return "map-match";
    case EdgeKind::kRefined:
      return "refined";
  }
  return "unknown";
}

FrameId AtlasGraph::AddFrame(std::unique_ptr<LocalMap> map, int64_t step) {
  MapFrame f;
  f.id = FrameCount();
  f.map = std::move(map);
  f.created_step = step;
  f.map_revision = NewMapRevision();
  f.edges.reserve(max_degree_);
  frames_.push_back(std::move(f));
  return frames_.back().id;
}

LocalMap& AtlasGraph::MutableMap(FrameId id) {
  MapFrame& f = frames_[id];
  f.map_revision = NewMapRevision();
  return *f.map;
}

void AtlasGraph::ReplaceMap(FrameId id, std::unique_ptr<LocalMap> map) {
  MapFrame& f = frames_[id];
  f.map = std::move(map);
  f.map_revision = NewMapRevision();
}

AddEdgeResult AtlasGraph::AddEdge(FrameId a, FrameId b, const UncertainPose& b_in_a, EdgeKind kind,
                                  int64_t step) {
  if (!HasFrame(a) || !HasFrame(b)) return AddEdgeResult::kBadFrame;
  if (a == b) return AddEdgeResult::kSameFrame;
  if (FindEdge(a, b) >= 0) return AddEdgeResult::kAlreadyAdjacent;
  if (static_cast<int>(frames_[a].edges.size()) >= max_degree_ ||
      static_cast<int>(frames_[b].edges.size()) >= max_degree_)
    return AddEdgeResult::kDegreeFull;
  AtlasEdge e;
  e.a = a;
  e.b = b;
  e.b_in_a = b_in_a;
  e.kind = kind;
  e.origin = kind;
  e.made_step = step;
  const int index = EdgeCount();
  edges_.push_back(e);
  frames_[a].edges.push_back(index);
  frames_[b].edges.push_back(index);
  return AddEdgeResult::kAdded;
}

int AtlasGraph::FindEdge(FrameId a, FrameId b) const {
  if (!HasFrame(a)) return -1;
  for (int32_t index : frames_[a].edges)
    if (OtherEnd(index, a) == b) return index;
  return -1;
}

FrameId AtlasGraph::OtherEnd(int index, FrameId from) const {
  const AtlasEdge& e = edges_[index];
  assert(e.a == from || e.b == from);
  return e.a == from ? e.b : e.a;
}

UncertainPose AtlasGraph::Transform(int index, FrameId from) const {
  const AtlasEdge& e = edges_[index];
  assert(e.a == from || e.b == from);
  return e.a == from ? e.b_in_a : Inverse(e.b_in_a);
}

void AtlasGraph::SetTransform(int index, FrameId from, const UncertainPose& to_in_from,
                              EdgeKind kind, int64_t step) {
  AtlasEdge& e = edges_[index];
  assert(e.a == from || e.b == from);
  e.b_in_a = e.a == from ? to_in_from : Inverse(to_in_from);
  e.kind = kind;
  if (kind == EdgeKind::kRefined) {
    e.refined_step = step;
    ++e.refinements;
  }
}

void AtlasGraph::RestoreRefinements(int index, int refinements, int64_t refined_step) {
  AtlasEdge& e = edges_[index];
  e.kind = EdgeKind::kRefined;
  e.refinements = refinements;
  e.refined_step = refined_step;
}

}  // namespace atlas
