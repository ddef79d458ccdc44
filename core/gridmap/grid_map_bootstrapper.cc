#include "core/gridmap/grid_map_bootstrapper.h"

#include <Eigen/Eigenvalues>
#include <algorithm>
#include <cmath>

#include "core/grid/branch_and_bound.h"
#include "core/grid/precomputation_grid.h"

namespace atlas {

PoseBootstrap GridMapBootstrapper::Solve(const LocalMap& map, const LocalMap& frame_map,
                                         const std::vector<JuvenileScan>& z,
                                         const UncertainPose& seed) const {
  PoseBootstrap out;
  const auto* frame = dynamic_cast<const GridLocalMap*>(&frame_map);
  if (z.empty() || frame == nullptr || frame->Grid().known_cells() == 0) return out;
  const GridBootstrapOptions& o = options_.bootstrap;
  // Z's returns in the current (last) robot frame.
  std::vector<Vec2> all;
  Pose2 k_in_current;
  for (int k = static_cast<int>(z.size()) - 1; k >= 0; --k) {
    const RigidTransform t(k_in_current);
    for (const Vec2& q : frame->AlignmentPoints(z[k].scan)) all.push_back(t.Apply(q));
    if (k > 0) k_in_current = Compose(k_in_current, Inverse(z[k].odometry_delta));
  }
  std::vector<Vec2> points;
  const size_t n = all.size(), max = static_cast<size_t>(o.max_points);
  for (size_t k = 0; k < std::min(n, max); ++k) points.push_back(all[n <= max ? k : k * n / max]);
  if (static_cast<int>(points.size()) < options_.grid.alignment.min_points) return out;

  const Eigen::SelfAdjointEigenSolver<Eigen::Matrix2d> eig(seed.cov.topLeftCorner<2, 2>());
  BranchAndBoundOptions search = options_.grid.search;
  search.linear_window = std::clamp(3.0 * std::sqrt(std::max(0.0, eig.eigenvalues()(1))),
                                    o.min_linear_window, o.max_linear_window);
  search.angular_window = std::clamp(3.0 * std::sqrt(std::max(0.0, seed.cov(2, 2))),
                                     o.min_angular_window, o.max_angular_window);
  search.min_score = o.min_score;
  const PrecomputationGridStack grids(frame->Grid(), search.depth);
  BranchAndBoundSearch bnb(grids, points, map.RobotPose().mean, search);
  if (bnb.Run(o.max_nodes) != SearchStatus::kDone) {
    out.outcome = BootstrapOutcome::kUndetermined;
    return out;
  }
  const BranchAndBoundResult& r = bnb.result();
  if (!r.best.found) return out;  // kFailed: Z does not lie in this grid
  if (r.margin < o.min_margin) {
    out.outcome = BootstrapOutcome::kUndetermined;
    return out;
  }
  ScanAligner aligner(options_.grid.alignment);
  const AlignmentResult a = aligner.Align(frame->Grid(), points, r.best.pose);
  if (a.outcome == AlignmentOutcome::kUnconstrained) out.outcome = BootstrapOutcome::kUndetermined;
  if (a.outcome != AlignmentOutcome::kAligned) return out;
  out.outcome = BootstrapOutcome::kSolved;
  out.pose = a.pose;
  out.pose.cov /= options_.information_scale;
  out.pose.cov.diagonal() += Vec3(options_.min_sigma_xy * options_.min_sigma_xy,
                                  options_.min_sigma_xy * options_.min_sigma_xy,
                                  options_.min_sigma_theta * options_.min_sigma_theta);
  return out;
}

}  // namespace atlas
