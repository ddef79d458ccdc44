#pragma once
// The relations metric of the Freiburg SLAM benchmark (Kümmerle, Steder, Dornhege, Ruhnke,
// Grisetti, Stachniss, Kleiner: "On measuring the accuracy of SLAM algorithms", Autonomous
// Robots 27(4), 2009). A relation (t1, t2, delta) states the true pose at t2 in the frame of
// the pose at t1. For an estimate P(t):
//
//   estimated delta  d = P(t1) (-) P(t2)            (Between, core/geometry/se2.h)
//   error            e = delta (-) d
//   translational    |e.xy|              metres
//   rotational       |wrap(e.theta)|     degrees
//
// reported as mean and standard deviation over all matched relations, and the same for the
// squared errors. A relation is matched when the estimate yields a relative pose for its two
// stamps; the rest are counted as unmatched and left out of the statistics.
//
// The estimate enters only through a RelativePoseLookup, so that it can be a plain trajectory
// (BetweenPosesOf) or, later, poses composed along Dijkstra paths of the atlas graph, where
// P(t1) and P(t2) may live in different map-frames and only their relative pose is defined.

#include <functional>
#include <optional>
#include <span>
#include <vector>

#include "core/common/time.h"
#include "core/eval/error_stats.h"
#include "core/eval/timed_trajectory.h"
#include "core/geometry/se2.h"

namespace atlas::eval {

struct Relation {
  Time t1{};
  Time t2{};
  Pose2 delta;  // pose at t2 in the frame of the pose at t1
};

// The estimated pose at t2 in the frame of the estimated pose at t1, or nullopt when the
// estimate has no pose for either stamp.
using RelativePoseLookup = std::function<std::optional<Pose2>(Time t1, Time t2)>;

// Timestamps of relation files are printed with 5 decimals: match within 1 ms.
inline constexpr Duration kDefaultMatchTolerance = std::chrono::milliseconds(1);

// Relative poses between the poses of `trajectory` nearest to t1 and t2 (each within
// `tolerance`). `trajectory` must outlive the returned function.
RelativePoseLookup BetweenPosesOf(const TimedTrajectory& trajectory,
                                  Duration tolerance = kDefaultMatchTolerance);

struct RelationError {
  size_t relation = 0;  // index into the relations given
  double translation_m = 0.0;
  double rotation_deg = 0.0;
};

struct RelationsScore {
  int64_t matched = 0;
  int64_t unmatched = 0;
  ErrorStats translation_m;
  ErrorStats rotation_deg;
  std::vector<RelationError> errors;  // matched relations, in the order given
};

// The error of one relation given the estimated relative pose.
RelationError RelationErrorOf(const Relation& relation, const Pose2& estimated_delta);

// Asks `estimate` once for each relation, in the order given.
RelationsScore ScoreRelations(std::span<const Relation> relations,
                              const RelativePoseLookup& estimate);

}  // namespace atlas::eval
