#include "core/gridmap/grid_map_matcher.h"

#include <Eigen/LU>
#include <algorithm>

#include "core/gridmap/dense_search.h"

namespace atlas {
namespace {

constexpr double kPriorGateChi2 = 16.27;  // 3 dof, 99.9 %

}  // namespace

MapMatch GridMapMatcher::Match(const LocalMap& a_map, const LocalMap& b_map,
                               const UncertainPose* prior) const {
  MapMatch m;
  const auto* a = dynamic_cast<const GridLocalMap*>(&a_map);
  const auto* b = dynamic_cast<const GridLocalMap*>(&b_map);
  if (a == nullptr || b == nullptr || prior == nullptr || b->Grid().known_cells() == 0) return m;
  const std::vector<Vec2> points = EvenSubsample(a->LastScanPoints(), options_.match.max_points);
  if (static_cast<int>(points.size()) < options_.grid.alignment.min_points) return m;
  const UncertainPose robot_a = a->RobotPose();
  const UncertainPose robot_b_prior = Compose(Inverse(*prior), robot_a);
  const DenseResult r =
      SearchAndRefine(grids_.Of(*b), b->Grid(), points, robot_b_prior, options_.match, options_);
  m.hypotheses = static_cast<int>(std::min<int64_t>(r.nodes, 1 << 30));
  switch (r.outcome) {
    case DenseOutcome::kWorkBound:
      m.reason = MapMatchReason::kWorkBound;
      return m;
    case DenseOutcome::kLowScore:
      m.reason = MapMatchReason::kTooLittleSupport;
      return m;
    case DenseOutcome::kRepetitive:
      m.result = MapMatchResult::kAmbiguous;
      m.reason = MapMatchReason::kRepetitive;
      return m;
    case DenseOutcome::kUnconstrained:
      m.reason = MapMatchReason::kDegenerate;
      return m;
    case DenseOutcome::kFound:
      break;
  }
  UncertainPose robot_b = r.pose;
  robot_b.cov += b->GridCovarianceNear(Vec2(robot_b.mean.x, robot_b.mean.y));
  const UncertainPose t = Compose(robot_a, Inverse(robot_b));
  const Vec3 v(t.mean.x - prior->mean.x, t.mean.y - prior->mean.y,
               WrapAngle(t.mean.theta - prior->mean.theta));
  const Mat3 gate = (t.cov + prior->cov).inverse();
  if (!gate.allFinite() || v.dot(gate * v) > kPriorGateChi2) {
    m.reason = MapMatchReason::kOutsidePrior;
    return m;
  }
  m.result = MapMatchResult::kAccepted;
  m.reason = MapMatchReason::kMatched;
  m.b_in_a = t;
  return m;
}

}  // namespace atlas
