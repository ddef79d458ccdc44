#include "core/eval/reference_score.h"

#include <cassert>
#include <cmath>
#include <numbers>

namespace atlas::eval {
namespace {

constexpr double kDegPerRad = 180.0 / std::numbers::pi;

}  // namespace

std::string ReferenceScoreOptions::Validate() const {
  if (match_tolerance < Duration::zero()) return "match_tolerance must be >= 0";
  if (step_count < 0) return "step_count must be >= 0";
  if (!(segment_length_m >= 0.0) || !std::isfinite(segment_length_m)) {
    return "segment_length_m must be >= 0";
  }
  if ((step_count > 0) == (segment_length_m > 0.0)) {
    return "set exactly one of step_count (--step) and segment_length_m (--segment)";
  }
  return {};
}

Pose2 BestRigidAlignment(std::span<const Pose2> from, std::span<const Pose2> to) {
  assert(from.size() == to.size());
  if (from.empty()) return Pose2{};
  const double n = static_cast<double>(from.size());
  Vec2 cf = Vec2::Zero(), ct = Vec2::Zero();
  for (size_t i = 0; i < from.size(); ++i) {
    cf += Vec2(from[i].x, from[i].y);
    ct += Vec2(to[i].x, to[i].y);
  }
  cf /= n;
  ct /= n;
  double sxx = 0.0, sxy = 0.0;  // sum of dot and cross products of centred positions
  for (size_t i = 0; i < from.size(); ++i) {
    const Vec2 a = Vec2(from[i].x, from[i].y) - cf;
    const Vec2 b = Vec2(to[i].x, to[i].y) - ct;
    sxx += a.dot(b);
    sxy += a.x() * b.y() - a.y() * b.x();
  }
  const double alpha = (sxx == 0.0 && sxy == 0.0) ? 0.0 : std::atan2(sxy, sxx);
  const double c = std::cos(alpha), s = std::sin(alpha);
  const Vec2 t = ct - Vec2(c * cf.x() - s * cf.y(), s * cf.x() + c * cf.y());
  return Pose2{t.x(), t.y(), WrapAngle(alpha)};
}

ReferenceScore ScoreAgainstReference(const TimedTrajectory& estimate,
                                     const TimedTrajectory& reference,
                                     const ReferenceScoreOptions& options) {
  assert(options.Validate().empty());
  ReferenceScore score;
  std::vector<Pose2> est, ref;
  for (const TimedPose& p : estimate.poses()) {
    const std::optional<Pose2> r = reference.PoseAt(p.stamp, options.match_tolerance);
    if (!r) {
      ++score.unmatched;
      continue;
    }
    est.push_back(p.pose);
    ref.push_back(*r);
  }
  score.matched = static_cast<int64_t>(est.size());
  const size_t n = est.size();

  // RPE.
  std::vector<double> rpe_t, rpe_r;
  const auto add_pair = [&](size_t i, size_t j) {
    const Relation rel{Time{}, Time{}, Between(ref[i], ref[j])};
    const RelationError e = RelationErrorOf(rel, Between(est[i], est[j]));
    rpe_t.push_back(e.translation_m);
    rpe_r.push_back(e.rotation_deg);
  };
  if (options.step_count > 0) {
    const size_t step = static_cast<size_t>(options.step_count);
    for (size_t i = 0; i + step < n; ++i) add_pair(i, i + step);
  } else if (n > 1) {
    std::vector<double> along(n, 0.0);  // reference path length from the first matched pose
    for (size_t k = 1; k < n; ++k) {
      along[k] = along[k - 1] + std::hypot(ref[k].x - ref[k - 1].x, ref[k].y - ref[k - 1].y);
    }
    score.reference_path_m = along[n - 1];
    size_t j = 1;
    for (size_t i = 0; i + 1 < n; ++i) {
      if (j <= i) j = i + 1;
      while (j < n && along[j] - along[i] < options.segment_length_m) ++j;
      if (j == n) break;
      add_pair(i, j);
    }
  }
  score.pairs = static_cast<int64_t>(rpe_t.size());
  score.rpe_translation_m = Summarize(rpe_t);
  score.rpe_rotation_deg = Summarize(rpe_r);

  // ATE after alignment.
  score.alignment = BestRigidAlignment(est, ref);
  std::vector<double> ate_t, ate_r;
  for (size_t k = 0; k < n; ++k) {
    const Pose2 a = Compose(score.alignment, est[k]);
    ate_t.push_back(std::hypot(a.x - ref[k].x, a.y - ref[k].y));
    ate_r.push_back(std::abs(WrapAngle(ref[k].theta - a.theta)) * kDegPerRad);
  }
  score.ate_translation_m = Summarize(ate_t);
  score.ate_rotation_deg = Summarize(ate_r);
  return score;
}

}  // namespace atlas::eval
