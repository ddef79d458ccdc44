#include "core/gridmap/grid_map_matcher.h"

#include <Eigen/LU>
#include <algorithm>
#include <cmath>

#include "core/gridmap/dense_search.h"

namespace atlas {
namespace {

constexpr double kPriorGateChi2 = 16.27;  // 3 dof, 99.9 %

// Whether the cell of `p` (a's frame) and its 8 neighbours are known and free in `a`.
bool FreeBlock(const ProbabilityGrid& a, uint16_t free_below, const Vec2& p) {
  const CellIndex c = a.limits().CellOf(p);
  for (int dy = -1; dy <= 1; ++dy) {
    for (int dx = -1; dx <= 1; ++dx) {
      const uint16_t v = a.Value(CellIndex{c.x + dx, c.y + dy});
      if (v == ProbabilityGrid::kUnknown || v >= free_below) return false;
    }
  }
  return true;
}

}  // namespace

FreeSpaceConflict FreeSpaceConflictOf(const ProbabilityGrid& a, const ProbabilityGrid& b,
                                      const Pose2& b_in_a, const Vec2& centre_b, double radius) {
  FreeSpaceConflict out;
  const GridLimits& lb = b.limits();
  if (lb.width == 0 || lb.height == 0 || a.known_cells() == 0) return out;
  const uint16_t occupied_from = b.ValueOfProbability(kFreeSpaceOccupied);
  const uint16_t free_below = a.ValueOfProbability(0.5);
  const CellIndex lo = lb.CellOf(centre_b - Vec2(radius, radius));
  const CellIndex hi = lb.CellOf(centre_b + Vec2(radius, radius));
  const RigidTransform to_a(b_in_a);
  const double r2 = radius * radius;
  for (int y = std::max(lo.y, 0); y <= std::min(hi.y, lb.height - 1); ++y) {
    for (int x = std::max(lo.x, 0); x <= std::min(hi.x, lb.width - 1); ++x) {
      const uint16_t v = b.values()[lb.IndexOf(CellIndex{x, y})];
      if (v == ProbabilityGrid::kUnknown || v < occupied_from) continue;
      const Vec2 p = lb.CenterOf(CellIndex{x, y});
      if ((p - centre_b).squaredNorm() > r2) continue;
      ++out.occupied;
      if (FreeBlock(a, free_below, to_a.Apply(p))) ++out.in_free;
    }
  }
  return out;
}

namespace {

class GridMatchSearch final : public MapMatchSearch {
 public:
  GridMatchSearch(const GridLocalMapOptions& options,
                  std::shared_ptr<PrecomputationGridStack> grids, std::vector<Vec2> points,
                  const UncertainPose& robot_a, const UncertainPose& prior)
      : options_(options),
        robot_a_(robot_a),
        prior_(prior),
        search_(std::move(grids), std::move(points), Compose(Inverse(prior), robot_a),
                options.match, options) {}

  bool Continue(const LocalMap& a_map, const LocalMap& b_map) override {
    if (done_) return true;
    const auto* a = dynamic_cast<const GridLocalMap*>(&a_map);
    const auto* b = dynamic_cast<const GridLocalMap*>(&b_map);
    if (a == nullptr || b == nullptr) return Finish();
    if (!search_.Continue(b->Grid(), options_.match.work_per_step)) return false;
    Judge(*a, *b);
    return Finish();
  }
  const MapMatch& Result() const override { return m_; }

 private:
  bool Finish() {
    done_ = true;
    return true;
  }
  void Judge(const GridLocalMap& a, const GridLocalMap& b);

  GridLocalMapOptions options_;
  UncertainPose robot_a_, prior_;
  DenseSearch search_;
  bool done_ = false;
  MapMatch m_;
};

void GridMatchSearch::Judge(const GridLocalMap& a, const GridLocalMap& b) {
  const DenseResult& r = search_.result();
  m_.hypotheses = static_cast<int>(std::min<int64_t>(r.nodes, 1 << 30));
  switch (r.outcome) {
    case DenseOutcome::kWorkBound:
      m_.reason = MapMatchReason::kWorkBound;
      return;
    case DenseOutcome::kLowScore:
      m_.reason = MapMatchReason::kTooLittleSupport;
      return;
    case DenseOutcome::kRepetitive:
      m_.result = MapMatchResult::kAmbiguous;
      m_.reason = MapMatchReason::kRepetitive;
      return;
    case DenseOutcome::kUnconstrained:
      m_.reason = MapMatchReason::kDegenerate;
      return;
    case DenseOutcome::kFound:
      break;
  }
  UncertainPose robot_b = r.pose;
  robot_b.cov += b.GridCovarianceNear(Vec2(robot_b.mean.x, robot_b.mean.y));
  const UncertainPose t = Compose(robot_a_, Inverse(robot_b));
  const Vec3 v(t.mean.x - prior_.mean.x, t.mean.y - prior_.mean.y,
               WrapAngle(t.mean.theta - prior_.mean.theta));
  const Mat3 gate = (t.cov + prior_.cov).inverse();
  if (!gate.allFinite() || v.dot(gate * v) > kPriorGateChi2) {
    m_.reason = MapMatchReason::kOutsidePrior;
    return;
  }
  const Vec2 at_a(robot_a_.mean.x, robot_a_.mean.y), at_b(robot_b.mean.x, robot_b.mean.y);
  const double b_in_a =
      FreeSpaceConflictOf(a.Grid(), b.Grid(), t.mean, at_b, kFreeSpaceRadius).Fraction();
  const double a_in_b =
      FreeSpaceConflictOf(b.Grid(), a.Grid(), Inverse(t.mean), at_a, kFreeSpaceRadius).Fraction();
  if (std::max(b_in_a, a_in_b) > options_.max_free_space_conflict) {
    m_.reason = MapMatchReason::kFreeSpace;
    return;
  }
  m_.result = MapMatchResult::kAccepted;
  m_.reason = MapMatchReason::kMatched;
  m_.b_in_a = t;
}

// A search that ended before it began (not both grids, no prior, too few points).
class NoSearch final : public MapMatchSearch {
 public:
  bool Continue(const LocalMap&, const LocalMap&) override { return true; }
  const MapMatch& Result() const override { return m_; }

 private:
  MapMatch m_;
};

}  // namespace

std::unique_ptr<MapMatchSearch> GridMapMatcher::Begin(const LocalMap& a_map, const LocalMap& b_map,
                                                      const UncertainPose* prior) const {
  const auto* a = dynamic_cast<const GridLocalMap*>(&a_map);
  const auto* b = dynamic_cast<const GridLocalMap*>(&b_map);
  if (a == nullptr || b == nullptr || prior == nullptr || b->Grid().known_cells() == 0)
    return std::make_unique<NoSearch>();
  std::vector<Vec2> points = SearchPoints(a->LastScanPoints(), options_.match);
  if (static_cast<int>(points.size()) < options_.grid.alignment.min_points)
    return std::make_unique<NoSearch>();
  return std::make_unique<GridMatchSearch>(options_, grids_.Of(*b), std::move(points),
                                           a->RobotPose(), *prior);
}

MapMatch GridMapMatcher::Match(const LocalMap& a, const LocalMap& b,
                               const UncertainPose* prior) const {
  const std::unique_ptr<MapMatchSearch> search = Begin(a, b, prior);
  while (!search->Continue(a, b)) {
  }
  return search->Result();
}

}  // namespace atlas
