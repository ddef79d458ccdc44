#include "daemon/lcm_out/reference_placement.h"

namespace atlas {

ReferencePlacement::ReferencePlacement(FrameId reference, int max_frames) : reference_(reference) {
  limits_.max_frames = max_frames;
}

void ReferencePlacement::Update(const Atlas& atlas, bool due) {
  const AtlasGraph& g = atlas.Graph();
  const DominantOutput d = atlas.Dominant();
  const bool grown = g.FrameCount() != frames_ || g.EdgeCount() != edges_;
  const bool missing = d.valid && projection_.Find(d.frame) == nullptr;
  if (!due && !(missing && grown)) return;
  frames_ = g.FrameCount();
  edges_ = g.EdgeCount();
  // A reference frame the atlas does not have yet leaves the projection empty.
  workspace_.Project(g, reference_, limits_, &projection_);
}

std::optional<PlacedPose> ReferencePlacement::Place(const DominantOutput& d) const {
  if (!d.valid) return std::nullopt;
  const ProjectedFrame* f = projection_.Find(d.frame);
  if (f == nullptr) return std::nullopt;
  return PlacedPose{Compose(f->pose, d.pose), f->pose, f->hops};
}

}  // namespace atlas
