#include "core/atlas/frame_components.h"

#include <cassert>
#include <utility>

namespace atlas {

void FrameComponents::Rebuild(const AtlasGraph& graph) {
  parent_.clear();
  size_.clear();
  for (int i = 0; i < graph.FrameCount(); ++i) AddFrame();
  for (const AtlasEdge& e : graph.Edges()) Join(e.a, e.b);
}

void FrameComponents::AddFrame() {
  parent_.push_back(static_cast<FrameId>(parent_.size()));
  size_.push_back(1);
}

FrameId FrameComponents::Root(FrameId f) {
  assert(f >= 0 && f < Count());
  while (parent_[f] != f) {
    parent_[f] = parent_[parent_[f]];
    f = parent_[f];
  }
  return f;
}

void FrameComponents::Join(FrameId a, FrameId b) {
  FrameId ra = Root(a), rb = Root(b);
  if (ra == rb) return;
  if (size_[ra] < size_[rb]) std::swap(ra, rb);
  parent_[rb] = ra;
  size_[ra] += size_[rb];
}

}  // namespace atlas
