#include "core/atlas/line_map_bootstrapper.h"

#include "core/localmap/bootstrap.h"
#include "core/localmap/line_ekf_map.h"

namespace atlas {

PoseBootstrap LineMapBootstrapper::Solve(const LocalMap& map, const LocalMap& /*frame_map*/,
                                         const std::vector<JuvenileScan>& z,
                                         const UncertainPose& /*seed*/) const {
  PoseBootstrap out;
  if (z.empty()) return out;
  std::vector<BootstrapScan> scans(z.size());
  // The robot frame of scan k in the current (last) robot frame: walk back over the increments.
  UncertainPose k_in_current;  // identity for the last scan
  for (int k = static_cast<int>(z.size()) - 1; k >= 0; --k) {
    scans[k].pose_in_current = k_in_current.mean;
    scans[k].pose_cov = k_in_current.cov;
    scans[k].lines = z[k].observation.RobotFrameLines(options_.extraction);
    if (k == 0) break;
    // z[k].odometry_delta is the pose of frame k in frame k-1.
    const UncertainPose delta{z[k].odometry_delta,
                              LineEkfMap::OdometryNoise(z[k].odometry_delta, options_.odometry)};
    k_in_current = Compose(k_in_current, Inverse(delta));
  }
  const BootstrapResult r =
      Bootstrap(map.Lines(), scans, map.RobotPose(), options_.bootstrap, options_.association);
  if (r.status == BootstrapStatus::kUnderconstrained) out.outcome = BootstrapOutcome::kUndetermined;
  if (r.status != BootstrapStatus::kSolved) return out;
  out.outcome = BootstrapOutcome::kSolved;
  out.pose = r.pose;
  return out;
}

}  // namespace atlas
