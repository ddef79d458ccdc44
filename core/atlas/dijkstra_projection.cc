#include "core/atlas/dijkstra_projection.h"

#include <algorithm>

namespace atlas {

const ProjectedFrame* Projection::Find(FrameId frame) const {
  for (const ProjectedFrame& e : entries)
    if (e.frame == frame) return &e;
  return nullptr;
}

bool DijkstraWorkspace::Project(const AtlasGraph& graph, FrameId source,
                                const ProjectionLimits& limits, Projection* out) {
  out->source = source;
  out->entries.clear();
  out->truncated = false;
  if (!graph.HasFrame(source)) return false;
  const size_t n = static_cast<size_t>(graph.FrameCount());
  if (visit_generation_.size() < n) {
    visit_generation_.resize(n, 0);
    slot_of_frame_.resize(n, -1);
  }
  if (++generation_ == 0) {
    std::fill(visit_generation_.begin(), visit_generation_.end(), 0);
    generation_ = 1;
  }
  candidates_.clear();
  settled_.clear();
  heap_.clear();
  const auto greater = [](const HeapItem& x, const HeapItem& y) { return x.rho > y.rho; };

  ProjectedFrame root;
  root.frame = source;
  root.pose = UncertainPose{};
  root.rho = 0.0;
  visit_generation_[source] = generation_;
  slot_of_frame_[source] = 0;
  candidates_.push_back(root);
  settled_.push_back(0);
  heap_.push_back({0.0, 0});

  while (!heap_.empty()) {
    std::pop_heap(heap_.begin(), heap_.end(), greater);
    const HeapItem top = heap_.back();
    heap_.pop_back();
    if (settled_[top.slot] || top.rho > candidates_[top.slot].rho) continue;  // stale entry
    if (top.rho > limits.max_rho || static_cast<int>(out->entries.size()) >= limits.max_frames) {
      out->truncated = true;
      break;
    }
    settled_[top.slot] = 1;
    const ProjectedFrame here = candidates_[top.slot];
    out->entries.push_back(here);
    for (int32_t edge : graph.Frame(here.frame).edges) {
      const FrameId next = graph.OtherEnd(edge, here.frame);
      const bool seen = visit_generation_[next] == generation_;
      if (seen && settled_[slot_of_frame_[next]]) continue;
      const UncertainPose pose = Compose(here.pose, graph.Transform(edge, here.frame));
      const double rho = pose.cov.determinant();
      if (seen && rho >= candidates_[slot_of_frame_[next]].rho) continue;
      ProjectedFrame cand;
      cand.frame = next;
      cand.parent = here.frame;
      cand.parent_edge = edge;
      cand.hops = here.hops + 1;
      cand.pose = pose;
      cand.rho = rho;
      int slot;
      if (seen) {
        slot = slot_of_frame_[next];
        candidates_[slot] = cand;
      } else {
        slot = static_cast<int>(candidates_.size());
        visit_generation_[next] = generation_;
        slot_of_frame_[next] = slot;
        candidates_.push_back(cand);
        settled_.push_back(0);
      }
      heap_.push_back({rho, slot});
      std::push_heap(heap_.begin(), heap_.end(), greater);
    }
  }
  return true;
}

Projection DijkstraProjection(const AtlasGraph& graph, FrameId source,
                              const ProjectionLimits& limits) {
  DijkstraWorkspace ws;
  Projection p;
  ws.Project(graph, source, limits, &p);
  return p;
}

}  // namespace atlas
