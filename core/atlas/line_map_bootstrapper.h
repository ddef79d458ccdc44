#pragma once
// w of eq. 12 for the line EKF local map: binds core/localmap's Bootstrap() (bootstrap.h) to
// the atlas's PoseBootstrapper interface.
//
// For the juvenile's accumulated scans Z, the lines in the robot frame of each scan are those
// of its observation (the same extraction the map uses, done once per scan: scan_observation.h),
// each scan's robot frame is placed in the current robot frame by composing the odometry
// increments backwards (covariance from the map's odometry noise model), and Bootstrap()
// solves the robot pose from the matched features alone. The seed (the juvenile's current pose)
// is passed only to propose correspondences, as bootstrap.h specifies; the solution does not
// otherwise depend on it.
//
// Outcomes (hypothesis.h): Bootstrap()'s kSolved is kSolved. kUnderconstrained (the matched map
// lines leave a direction free, e.g. only the two parallel walls of a corridor) is
// kUndetermined: Z does not determine the pose yet, and a scan or two more may see a crossing
// wall, so the atlas keeps accumulating Z and tries w again until the end of probation (Section
// III-E kills a hypothesis when w fails, not while it cannot decide). kTooFewMatches and
// kInconsistent (the scans contradict the map) are kFailed. On the six corrected logs this keeps
// juveniles alive that re-enter a frame along a corridor: intel's returns more than 0.5 m off
// went from 48 and 50 of 108 to 19 and 10 (seeds 1 and 2), with no false loop closure
// (docs/design.md, "III-B. Hypotheses"). Treating kTooFewMatches the same way too brought false
// closures.

#include "core/atlas/hypothesis.h"
#include "core/localmap/localmap_options.h"

namespace atlas {

class LineMapBootstrapper : public PoseBootstrapper {
 public:
  // `options` must be valid (the same options the maps were made with).
  explicit LineMapBootstrapper(const LocalMapOptions& options) : options_(options) {}
  // Solves against `map`'s lines (the juvenile's trial map), associating from its robot pose;
  // `frame_map` and `seed` are not used.
  PoseBootstrap Solve(const LocalMap& map, const LocalMap& frame_map,
                      const std::vector<JuvenileScan>& z, const UncertainPose& seed) const override;

 private:
  LocalMapOptions options_;
};

}  // namespace atlas
