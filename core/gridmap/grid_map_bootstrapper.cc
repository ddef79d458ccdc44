#include "core/gridmap/grid_map_bootstrapper.h"

#include "core/gridmap/dense_search.h"

namespace atlas {

PoseBootstrap GridMapBootstrapper::Solve(const LocalMap& map, const LocalMap& frame_map,
                                         const std::vector<JuvenileScan>& z,
                                         const UncertainPose& seed) const {
  PoseBootstrap out;
  const auto* frame = dynamic_cast<const GridLocalMap*>(&frame_map);
  if (z.empty() || frame == nullptr || frame->Grid().known_cells() == 0) return out;
  // Z's returns in the current (last) robot frame.
  std::vector<Vec2> all;
  Pose2 k_in_current;
  for (int k = static_cast<int>(z.size()) - 1; k >= 0; --k) {
    const RigidTransform t(k_in_current);
    for (const Vec2& q : frame->AlignmentPoints(z[k].observation.scan())) all.push_back(t.Apply(q));
    if (k > 0) k_in_current = Compose(k_in_current, Inverse(z[k].odometry_delta));
  }
  const std::vector<Vec2> points = EvenSubsample(all, options_.bootstrap.max_points);
  if (static_cast<int>(points.size()) < options_.grid.alignment.min_points) return out;
  const DenseResult r =
      SearchAndRefine(grids_.Of(*frame), frame->Grid(), points,
                      UncertainPose{map.RobotPose().mean, seed.cov}, options_.bootstrap, options_);
  switch (r.outcome) {
    case DenseOutcome::kFound:
      out.outcome = BootstrapOutcome::kSolved;
      out.pose = r.pose;
      break;
    case DenseOutcome::kLowScore:
      out.outcome = BootstrapOutcome::kFailed;  // Z does not lie in this grid
      break;
    case DenseOutcome::kWorkBound:
    case DenseOutcome::kRepetitive:
    case DenseOutcome::kUnconstrained:
      out.outcome = BootstrapOutcome::kUndetermined;
      break;
  }
  return out;
}

}  // namespace atlas
