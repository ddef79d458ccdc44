#include "core/gridmap/dense_search.h"

#include <Eigen/Eigenvalues>
#include <algorithm>
#include <cmath>

#include "core/grid/branch_and_bound.h"
#include "core/grid/scan_alignment.h"

namespace atlas {

std::shared_ptr<PrecomputationGridStack> PrecomputedGrids::Of(const GridLocalMap& map) {
  for (const Cached& c : cache_) {
    if (c.revision == map.Revision()) return c.grids;
  }
  Cached fresh{map.Revision(),
               std::make_shared<PrecomputationGridStack>(
                   map.Grid(), depth_, PrecomputationGridStack::Building::kInSlices)};
  if (cache_.size() < kCached) {
    cache_.push_back(std::move(fresh));
    return cache_.back().grids;
  }
  Cached& slot = cache_[next_++ % kCached];
  slot = std::move(fresh);
  return slot.grids;
}

std::vector<Vec2> EvenSubsample(const std::vector<Vec2>& points, int max) {
  const size_t n = points.size(), m = static_cast<size_t>(std::max(max, 0));
  if (n <= m) return points;
  std::vector<Vec2> out;
  out.reserve(m);
  for (size_t k = 0; k < m; ++k) out.push_back(points[k * n / m]);
  return out;
}

std::vector<Vec2> SearchPoints(const std::vector<Vec2>& points, const GridSearchOptions& options) {
  std::vector<Vec2> near;
  near.reserve(points.size());
  for (const Vec2& p : points)
    if (p.norm() <= options.max_point_range) near.push_back(p);
  return EvenSubsample(near, options.max_points);
}

namespace {

// Of the prior's position (x, y), metres.
double ThreeSigmaOfWidestAxis(const Mat3& cov) {
  const Eigen::SelfAdjointEigenSolver<Eigen::Matrix2d> eig(cov.topLeftCorner<2, 2>());
  return 3.0 * std::sqrt(std::max(0.0, eig.eigenvalues()(1)));
}

}  // namespace

DenseSearch::DenseSearch(std::shared_ptr<PrecomputationGridStack> grids, std::vector<Vec2> points,
                         const UncertainPose& prior, const GridSearchOptions& search,
                         const GridLocalMapOptions& map)
    : grids_(std::move(grids)),
      points_(std::move(points)),
      prior_(prior),
      search_(search),
      map_(map),
      prior_three_sigma_(ThreeSigmaOfWidestAxis(prior.cov)) {}

DenseSearch::SliceEnd DenseSearch::RunSlice(BranchAndBoundSearch& search, int64_t per_node,
                                            int64_t* work) const {
  const int64_t left = search_.max_nodes - search.result().nodes;
  const int64_t before = search.result().nodes;
  const SearchStatus status =
      left > 0 ? search.Run(std::min(left, std::max<int64_t>(1, *work / per_node)))
               : SearchStatus::kRunning;
  *work -= (search.result().nodes - before) * per_node;
  if (status == SearchStatus::kDone) return SliceEnd::kDone;
  return search.result().nodes < search_.max_nodes ? SliceEnd::kMore : SliceEnd::kWorkBound;
}

bool DenseSearch::EndWorkBound() {
  result_.outcome = DenseOutcome::kWorkBound;
  phase_ = Phase::kDone;
  return true;
}

bool DenseSearch::Continue(const ProbabilityGrid& grid, int64_t work) {
  const int64_t per_node = std::max<int64_t>(1, static_cast<int64_t>(points_.size()));
  work = std::max<int64_t>(work, per_node);
  const int64_t given = work;
  switch (phase_) {
    case Phase::kPrecompute:
      work -= grids_->Build(work);
      if (!grids_->complete() || work < per_node) return false;
      phase_ = Phase::kSearch;
      [[fallthrough]];
    case Phase::kSearch: {
      if (!bnb_) {
        BranchAndBoundOptions o = map_.grid.search;
        o.linear_window =
            std::clamp(prior_three_sigma_, search_.min_linear_window, search_.max_linear_window);
        o.angular_window = std::clamp(3.0 * std::sqrt(std::max(0.0, prior_.cov(2, 2))),
                                      search_.min_angular_window, search_.max_angular_window);
        o.min_score = search_.min_score;
        o.rival_margin = search_.min_margin;
        bnb_ = std::make_unique<BranchAndBoundSearch>(*grids_, points_, prior_.mean, o);
        work -= static_cast<int64_t>(bnb_->window().headings()) * per_node;
      }
      const SliceEnd end = RunSlice(*bnb_, per_node, &work);
      result_.nodes = bnb_->result().nodes;
      if (end == SliceEnd::kMore) return false;
      if (end == SliceEnd::kWorkBound) return EndWorkBound();
      const BranchAndBoundResult& r = bnb_->result();
      result_.score = r.best.score;
      result_.margin = r.margin;
      if (!r.best.found) {  // kLowScore
        phase_ = Phase::kDone;
        return true;
      }
      if (r.margin < search_.min_margin) {
        result_.outcome = DenseOutcome::kRepetitive;
        phase_ = Phase::kDone;
        return true;
      }
      phase_ = Phase::kBeyond;
      [[fallthrough]];
    }
    case Phase::kBeyond: {
      const double wide = std::min(prior_three_sigma_, search_.max_repetition_window);
      if (wide > search_.max_linear_window) {
        const MatchPlacement& best = bnb_->result().best;
        if (!beyond_) {
          BranchAndBoundOptions o = map_.grid.search;
          o.linear_window = wide;
          o.angular_window = 0.0;
          o.min_score = std::max(0.0, best.score - search_.min_margin);
          o.rival_margin = search_.min_margin;
          const Placement at{0, best.placement.x, best.placement.y};
          beyond_ = std::make_unique<BranchAndBoundSearch>(
              *grids_, points_, Pose2{prior_.mean.x, prior_.mean.y, best.pose.theta}, o, &at);
          work -= per_node;
        }
        const SliceEnd end = RunSlice(*beyond_, per_node, &work);
        result_.nodes = bnb_->result().nodes + beyond_->result().nodes;
        if (end == SliceEnd::kMore) return false;
        if (end == SliceEnd::kWorkBound) return EndWorkBound();
        if (beyond_->result().best.found) {
          result_.margin = std::min(result_.margin, best.score - beyond_->result().best.score);
          result_.outcome = DenseOutcome::kRepetitive;
          phase_ = Phase::kDone;
          return true;
        }
      }
      phase_ = Phase::kRefine;
      // The refinement costs about a scan alignment: in this call only when half of it is left.
      if (work < given / 2) return false;
      [[fallthrough]];
    }
    case Phase::kRefine: {
      ScanAligner aligner(map_.grid.alignment);
      const AlignmentResult a = aligner.Align(grid, points_, bnb_->result().best.pose);
      phase_ = Phase::kDone;
      if (a.outcome != AlignmentOutcome::kAligned) {
        result_.outcome = DenseOutcome::kUnconstrained;
        return true;
      }
      result_.outcome = DenseOutcome::kFound;
      result_.pose = a.pose;
      result_.pose.cov /= map_.information_scale;
      const double xy = std::max(map_.min_sigma_xy, search_.min_sigma_xy);
      const double th = std::max(map_.min_sigma_theta, search_.min_sigma_theta);
      result_.pose.cov.diagonal() += Vec3(xy * xy, xy * xy, th * th);
      return true;
    }
    case Phase::kDone:
      return true;
  }
  return true;
}

}  // namespace atlas
