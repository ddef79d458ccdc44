#pragma once
// Where the dominant frame lies in one fixed frame, the reference frame, for
// ATLAS_REFERENCE_POSE (docs/lcm.md): the Dijkstra projection from the reference frame (paper,
// Section III-A), kept between steps.
//
// Contract:
// - Update() after a step re-projects when `due` (the caller's period: the graph message's) or
//   when the dominant frame is not in the kept projection and the graph has gained frames or
//   edges since it was made (a new frame from Genesis, a map-match joining an island): a pose
//   of a new frame is placed from the step that made it, and an unreachable frame costs no
//   projection per step.
// - Fixed budget: the projection settles at most `max_frames` frames, nearest (least rho)
//   first; a dominant frame beyond them is not placed. A DijkstraWorkspace is reused: no
//   allocation once warm.
// - Place() composes the kept placement of the pose's frame with the pose (eq. 2): between
//   two re-projections the placement may lag edge refinements along its path.

#include <optional>

#include "core/atlas/atlas.h"
#include "core/atlas/dijkstra_projection.h"

namespace atlas {

struct PlacedPose {
  UncertainPose pose;   // the robot in the reference frame
  UncertainPose frame;  // the pose's frame in the reference frame
  int hops = 0;
};

class ReferencePlacement {
 public:
  static constexpr int kDefaultMaxFrames = 4096;
  explicit ReferencePlacement(FrameId reference, int max_frames = kDefaultMaxFrames);

  FrameId reference() const { return reference_; }
  void Update(const Atlas& atlas, bool due);
  // nullopt when `d` is not valid or its frame is not in the kept projection.
  std::optional<PlacedPose> Place(const DominantOutput& d) const;

 private:
  FrameId reference_;
  ProjectionLimits limits_;
  DijkstraWorkspace workspace_;
  Projection projection_;
  int frames_ = -1, edges_ = -1;  // the graph's size when projection_ was made
};

}  // namespace atlas
