#include "core/gridmap/dense_search.h"

#include <Eigen/Eigenvalues>
#include <algorithm>
#include <cmath>

#include "core/grid/branch_and_bound.h"
#include "core/grid/scan_alignment.h"

namespace atlas {

const PrecomputationGridStack& PrecomputedGrids::Of(const GridLocalMap& map) {
  for (const Cached& c : cache_) {
    if (c.revision == map.Revision()) return *c.grids;
  }
  Cached fresh{map.Revision(), std::make_unique<PrecomputationGridStack>(map.Grid(), depth_)};
  if (cache_.size() < kCached) {
    cache_.push_back(std::move(fresh));
    return *cache_.back().grids;
  }
  Cached& slot = cache_[next_++ % kCached];
  slot = std::move(fresh);
  return *slot.grids;
}

std::vector<Vec2> EvenSubsample(const std::vector<Vec2>& points, int max) {
  const size_t n = points.size(), m = static_cast<size_t>(std::max(max, 0));
  if (n <= m) return points;
  std::vector<Vec2> out;
  out.reserve(m);
  for (size_t k = 0; k < m; ++k) out.push_back(points[k * n / m]);
  return out;
}

DenseResult SearchAndRefine(const PrecomputationGridStack& grids, const ProbabilityGrid& grid,
                            const std::vector<Vec2>& points, const UncertainPose& prior,
                            const GridSearchOptions& o, const GridLocalMapOptions& map) {
  DenseResult out;
  const Eigen::SelfAdjointEigenSolver<Eigen::Matrix2d> eig(prior.cov.topLeftCorner<2, 2>());
  BranchAndBoundOptions search = map.grid.search;
  search.linear_window = std::clamp(3.0 * std::sqrt(std::max(0.0, eig.eigenvalues()(1))),
                                    o.min_linear_window, o.max_linear_window);
  search.angular_window = std::clamp(3.0 * std::sqrt(std::max(0.0, prior.cov(2, 2))),
                                     o.min_angular_window, o.max_angular_window);
  search.min_score = o.min_score;
  BranchAndBoundSearch bnb(grids, points, prior.mean, search);
  const SearchStatus status = bnb.Run(o.max_nodes);
  const BranchAndBoundResult& r = bnb.result();
  out.nodes = r.nodes;
  if (status != SearchStatus::kDone) {
    out.outcome = DenseOutcome::kWorkBound;
    return out;
  }
  out.score = r.best.score;
  out.margin = r.margin;
  if (!r.best.found) return out;  // kLowScore
  if (r.margin < o.min_margin) {
    out.outcome = DenseOutcome::kRepetitive;
    return out;
  }
  ScanAligner aligner(map.grid.alignment);
  const AlignmentResult a = aligner.Align(grid, points, r.best.pose);
  if (a.outcome != AlignmentOutcome::kAligned) {
    out.outcome = DenseOutcome::kUnconstrained;
    return out;
  }
  out.outcome = DenseOutcome::kFound;
  out.pose = a.pose;
  out.pose.cov /= map.information_scale;
  const double xy = std::max(map.min_sigma_xy, o.min_sigma_xy);
  const double th = std::max(map.min_sigma_theta, o.min_sigma_theta);
  out.pose.cov.diagonal() += Vec3(xy * xy, xy * xy, th * th);
  return out;
}

}  // namespace atlas
