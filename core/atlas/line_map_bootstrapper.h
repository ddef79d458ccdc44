#pragma once
// w of eq. 12 for the line EKF local map: binds core/localmap's Bootstrap() (bootstrap.h) to
// the atlas's PoseBootstrapper interface.
//
// For the juvenile's accumulated scans Z, lines are extracted in the robot frame of each scan
// (the same extraction the map uses), each scan's robot frame is placed in the current robot
// frame by composing the odometry increments backwards (covariance from the map's odometry
// noise model), and Bootstrap() solves the robot pose from the matched features alone. The
// seed (the juvenile's current pose) is passed only to propose correspondences, as bootstrap.h
// specifies; the solution does not otherwise depend on it.

#include "core/atlas/hypothesis.h"
#include "core/localmap/localmap_options.h"

namespace atlas {

class LineMapBootstrapper : public PoseBootstrapper {
 public:
  // `options` must be valid (the same options the maps were made with).
  explicit LineMapBootstrapper(const LocalMapOptions& options) : options_(options) {}
  // Solves against `map`'s lines (the juvenile's trial map); `frame_map` is not used.
  PoseBootstrap Solve(const LocalMap& map, const LocalMap& frame_map,
                      const std::vector<JuvenileScan>& z) const override;

 private:
  LocalMapOptions options_;
};

}  // namespace atlas
