#include "core/eval/atlas_relations.h"

#include <algorithm>

namespace atlas::eval {

std::string BuildGraphFromEdges(int frame_count, std::span<const EdgeRow> edges, AtlasGraph* out) {
  // The degree bound is the largest degree among the edges (AtlasGraph reserves it per frame).
  std::vector<int> degree(static_cast<size_t>(std::max(frame_count, 0)), 0);
  for (const EdgeRow& e : edges)
    for (FrameId f : {e.from, e.to})
      if (f >= 0 && f < frame_count) ++degree[static_cast<size_t>(f)];
  int max_degree = 1;
  for (int d : degree) max_degree = std::max(max_degree, d);
  AtlasGraph graph(max_degree);
  for (int f = 0; f < frame_count; ++f) graph.AddFrame(nullptr);
  for (size_t i = 0; i < edges.size(); ++i) {
    const EdgeRow& e = edges[i];
    const char* why = nullptr;
    switch (graph.AddEdge(e.from, e.to, e.to_in_from, e.kind)) {
      case AddEdgeResult::kAdded:
        break;
      case AddEdgeResult::kBadFrame:
        why = "names a frame that does not exist";
        break;
      case AddEdgeResult::kSameFrame:
        why = "joins a frame to itself";
        break;
      case AddEdgeResult::kAlreadyAdjacent:
        why = "joins two frames that an earlier edge already joins";
        break;
      case AddEdgeResult::kDegreeFull:
        why = "exceeds the degree bound";
        break;
    }
    if (why != nullptr) {
      return "edge " + std::to_string(i + 1) + " (" + std::to_string(e.from) + " -> " +
             std::to_string(e.to) + ") " + why;
    }
  }
  *out = std::move(graph);
  return {};
}

namespace {

std::vector<TimedPose> StampsAndPoses(std::vector<FramePose>& rows) {
  std::stable_sort(rows.begin(), rows.end(),
                   [](const FramePose& a, const FramePose& b) { return a.stamp < b.stamp; });
  std::vector<TimedPose> out;
  out.reserve(rows.size());
  for (const FramePose& r : rows) out.push_back(TimedPose{r.stamp, r.pose});
  return out;
}

}  // namespace

DijkstraComposedPoses::DijkstraComposedPoses(std::vector<FramePose> trajectory,
                                             const AtlasGraph& graph, Duration tolerance)
    : poses_(StampsAndPoses(trajectory)), graph_(graph), tolerance_(tolerance) {
  // TimedTrajectory's stable sort keeps the order of the already sorted rows.
  frame_.reserve(trajectory.size());
  for (const FramePose& r : trajectory) frame_.push_back(r.frame);
}

const Projection& DijkstraComposedPoses::ProjectionFrom(FrameId source) {
  auto it = projections_.find(source);
  if (it == projections_.end()) {
    it = projections_.emplace(source, Projection{}).first;
    workspace_.Project(graph_, source, ProjectionLimits{}, &it->second);
  }
  return it->second;
}

const char* FrameJoinName(FrameJoin join) {
  switch (join) {
    case FrameJoin::kSameFrame:
      return "same";
    case FrameJoin::kNeighbours:
      return "neighbours";
    case FrameJoin::kThroughMapMatch:
      return "map-match";
    case FrameJoin::kChain:
      return "chain";
  }
  return "?";
}

std::optional<Pose2> DijkstraComposedPoses::operator()(Time t1, Time t2, FrameJoin* join) {
  const std::optional<size_t> i1 = poses_.IndexAt(t1, tolerance_);
  const std::optional<size_t> i2 = poses_.IndexAt(t2, tolerance_);
  if (!i1 || !i2) {
    ++counts_.unmatched;
    return std::nullopt;
  }
  const Pose2& p1 = poses_.poses()[*i1].pose;
  const Pose2& p2 = poses_.poses()[*i2].pose;
  const FrameId f1 = frame_[*i1], f2 = frame_[*i2];
  if (f1 == f2) {
    ++counts_.same_frame;
    if (join != nullptr) *join = FrameJoin::kSameFrame;
    return Between(p1, p2);
  }
  const Projection& projection = ProjectionFrom(f1);
  const ProjectedFrame* e = projection.Find(f2);
  if (e == nullptr) {
    ++counts_.unconnected;
    return std::nullopt;
  }
  ++counts_.cross_frame;
  bool map_match = false;
  for (const ProjectedFrame* on = e; on->parent != kNoFrame; on = projection.Find(on->parent))
    map_match |= graph_.Edge(on->parent_edge).kind == EdgeKind::kMapMatch;
  const FrameJoin j = map_match      ? FrameJoin::kThroughMapMatch
                      : e->hops == 1 ? FrameJoin::kNeighbours
                                     : FrameJoin::kChain;
  ++(j == FrameJoin::kThroughMapMatch ? counts_.through_map_match
     : j == FrameJoin::kNeighbours    ? counts_.neighbours
                                      : counts_.chain);
  if (join != nullptr) *join = j;
  return Between(p1, Compose(e->pose.mean, p2));
}

}  // namespace atlas::eval
