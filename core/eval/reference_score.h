#pragma once
// Scoring an estimated trajectory against a reference trajectory (simulator ground truth, the
// GMapping poses of the corrected logs). Estimated poses are matched to reference poses by stamp.
//
// Relative pose error (RPE): over pairs of matched poses (i, j), either a fixed number of
// matched poses apart (j = i + step_count) or a fixed travelled distance apart (j is the first
// pose after i whose reference path length from i reaches segment_length_m):
//     e = (ref_i (-) ref_j) (-) (est_i (-) est_j), errors |e.xy| (m) and |wrap(e.theta)| (deg)
// the relations metric (relations_metric.h) applied to relations drawn from the reference.
//
// Absolute trajectory error (ATE): the estimate is first moved by the rigid transform (rotation
// and translation, no scale) that best aligns its positions to the reference in the
// least-squares sense (closed form, Horn / Umeyama in 2D); then per pose |ref.xy - aligned.xy|
// (m) and |wrap(ref.theta - aligned.theta)| (deg).

#include <string>

#include "core/eval/error_stats.h"
#include "core/eval/relations_metric.h"
#include "core/eval/timed_trajectory.h"

namespace atlas::eval {

struct ReferenceScoreOptions {
  Duration match_tolerance = kDefaultMatchTolerance;
  // Exactly one of the two is > 0 (atlas-eval: --step N or --segment M).
  int step_count = 0;
  double segment_length_m = 1.0;

  // Empty when valid, else what is wrong.
  std::string Validate() const;
};

struct ReferenceScore {
  int64_t matched = 0;    // estimated poses with a reference pose within the tolerance
  int64_t unmatched = 0;  // estimated poses without one
  int64_t pairs = 0;      // RPE pairs (0: no pair was that far apart; the RPE means nothing)
  double reference_path_m = 0.0;  // reference path length over the matched poses
  ErrorStats rpe_translation_m;
  ErrorStats rpe_rotation_deg;
  ErrorStats ate_translation_m;
  ErrorStats ate_rotation_deg;
  Pose2 alignment;  // Compose(alignment, estimated pose) is the aligned estimate
};

// The rigid transform T minimising sum |T(from_i) - to_i|^2 over positions; as a Pose2,
// Compose(T, p) maps a pose of the `from` frame into the `to` frame. Identity when empty.
Pose2 BestRigidAlignment(std::span<const Pose2> from, std::span<const Pose2> to);

// `options` must be valid.
ReferenceScore ScoreAgainstReference(const TimedTrajectory& estimate,
                                     const TimedTrajectory& reference,
                                     const ReferenceScoreOptions& options);

}  // namespace atlas::eval
