#include "core/eval/relations_metric.h"

#include <cmath>
#include <numbers>

namespace atlas::eval {

RelativePoseLookup BetweenPosesOf(const TimedTrajectory& trajectory, Duration tolerance) {
  return [&trajectory, tolerance](Time t1, Time t2) -> std::optional<Pose2> {
    const std::optional<Pose2> p1 = trajectory.PoseAt(t1, tolerance);
    const std::optional<Pose2> p2 = trajectory.PoseAt(t2, tolerance);
    if (!p1 || !p2) return std::nullopt;
    return Between(*p1, *p2);
  };
}

RelationError RelationErrorOf(const Relation& relation, const Pose2& estimated_delta) {
  const Pose2 e = Between(relation.delta, estimated_delta);
  RelationError out;
  out.translation_m = std::hypot(e.x, e.y);
  out.rotation_deg = std::abs(WrapAngle(e.theta)) * 180.0 / std::numbers::pi;
  return out;
}

RelationsScore ScoreRelations(std::span<const Relation> relations,
                              const RelativePoseLookup& estimate) {
  RelationsScore score;
  std::vector<double> trans, rot;
  for (size_t i = 0; i < relations.size(); ++i) {
    const std::optional<Pose2> d = estimate(relations[i].t1, relations[i].t2);
    if (!d) {
      ++score.unmatched;
      continue;
    }
    ++score.matched;
    RelationError e = RelationErrorOf(relations[i], *d);
    e.relation = i;
    trans.push_back(e.translation_m);
    rot.push_back(e.rotation_deg);
    score.errors.push_back(e);
  }
  score.translation_m = Summarize(trans);
  score.rotation_deg = Summarize(rot);
  return score;
}

}  // namespace atlas::eval
