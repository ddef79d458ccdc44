#include "core/gridmap/grid_map_bootstrapper.h"

#include "core/gridmap/dense_search.h"

namespace atlas {

namespace {

PoseBootstrap ToBootstrap(const DenseResult& r) {
  PoseBootstrap out;
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

// Z's returns in the current (last) robot frame that w searches for (SearchPoints).
std::vector<Vec2> ZPoints(const GridLocalMap& frame, const std::vector<JuvenileScan>& z,
                          const GridSearchOptions& search) {
  std::vector<Vec2> all;
  Pose2 k_in_current;
  for (int k = static_cast<int>(z.size()) - 1; k >= 0; --k) {
    const RigidTransform t(k_in_current);
    for (const Vec2& q : frame.AlignmentPoints(z[k].observation.scan())) all.push_back(t.Apply(q));
    if (k > 0) k_in_current = Compose(k_in_current, Inverse(z[k].odometry_delta));
  }
  return SearchPoints(all, search);
}

class GridBootstrapSearch final : public BootstrapSearch {
 public:
  GridBootstrapSearch(const GridLocalMapOptions& options, DenseSearch search)
      : options_(options), search_(std::move(search)) {}
  bool Continue(const LocalMap&, const LocalMap& frame_map,
                const std::vector<JuvenileScan>&) override {
    const auto* frame = dynamic_cast<const GridLocalMap*>(&frame_map);
    if (frame == nullptr) return true;  // kFailed
    if (!search_.Continue(frame->Grid(), options_.bootstrap.work_per_step)) return false;
    result_ = ToBootstrap(search_.result());
    return true;
  }
  PoseBootstrap TakeResult() override { return std::move(result_); }

 private:
  GridLocalMapOptions options_;
  DenseSearch search_;
  PoseBootstrap result_;
};

class FailedBootstrap final : public BootstrapSearch {
 public:
  bool Continue(const LocalMap&, const LocalMap&, const std::vector<JuvenileScan>&) override {
    return true;
  }
  PoseBootstrap TakeResult() override { return {}; }
};

}  // namespace

std::unique_ptr<BootstrapSearch> GridMapBootstrapper::Begin(const LocalMap& map,
                                                            const LocalMap& frame_map,
                                                            const std::vector<JuvenileScan>& z,
                                                            const UncertainPose& seed) const {
  const auto* frame = dynamic_cast<const GridLocalMap*>(&frame_map);
  if (z.empty() || frame == nullptr || frame->Grid().known_cells() == 0)
    return std::make_unique<FailedBootstrap>();
  std::vector<Vec2> points = ZPoints(*frame, z, options_.bootstrap);
  if (static_cast<int>(points.size()) < options_.grid.alignment.min_points)
    return std::make_unique<FailedBootstrap>();
  return std::make_unique<GridBootstrapSearch>(
      options_,
      DenseSearch(grids_.Of(*frame), std::move(points),
                  UncertainPose{map.RobotPose().mean, seed.cov}, options_.bootstrap, options_));
}

PoseBootstrap GridMapBootstrapper::Solve(const LocalMap& map, const LocalMap& frame_map,
                                         const std::vector<JuvenileScan>& z,
                                         const UncertainPose& seed) const {
  const std::unique_ptr<BootstrapSearch> search = Begin(map, frame_map, z, seed);
  while (!search->Continue(map, frame_map, z)) {
  }
  return search->TakeResult();
}

}  // namespace atlas
