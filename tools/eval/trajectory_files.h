#pragma once
// The text of atlas-eval and atlas-carmen (docs/formats.md), and trajectories derived from
// CARMEN logs. Parsers take text and a source name for messages (rows: formats/text_rows.h).
//
//   trajectory file   one pose per line: "timestamp x y theta" (formats/pose_file.h).
//   relations file    Freiburg SLAM benchmark: "t1 t2 x y z roll pitch yaw", the pose at t2 in
//                     the frame of the pose at t1 (z, roll and pitch are ignored).

#include <span>
#include <string>
#include <string_view>
#include <vector>

#include "core/eval/atlas_relations.h"
#include "core/eval/reference_score.h"
#include "core/eval/relations_metric.h"
#include "core/eval/timed_trajectory.h"
#include "logs/carmen/carmen_log.h"

namespace atlas::eval {

// A trajectory file (formats/pose_file.h), sorted by stamp; a file without rows is the error
// "<source>: no poses".
struct TrajectoryParse {
  TimedTrajectory trajectory;
  std::string error;  // "<source>:<line>: <what>"; empty when valid
};
TrajectoryParse ParseTrajectory(std::string_view text, const std::string& source);

struct RelationsParse {
  std::vector<Relation> relations;
  std::string error;
};
RelationsParse ParseRelations(std::string_view text, const std::string& source);

// atlas-eval --errors: "t1 t2 translation_m rotation_deg" per matched relation of `score`
// (scored from `relations`), in the relations' order, with a header comment. With `joins` (one
// per score.errors entry), a fifth column: how the atlas joins the two poses (FrameJoinName).
std::string FormatRelationErrors(const std::vector<Relation>& relations,
                                 const RelationsScore& score,
                                 std::span<const FrameJoin> joins = {});

// The odometry pose at the stamp of every laser scan among `events` (time-ordered), linearly
// interpolated between the odometry samples around it (heading along the shorter arc). Scans
// before the first or after the last odometry sample are left out.
TimedTrajectory OdometryAtScans(const std::vector<carmen::CarmenEvent>& events);

// The reference poses of a log's laser lines (read with reference_trajectory set).
TimedTrajectory ReferenceAtScans(const carmen::CarmenLog& log);

// Human-readable and JSON summaries.
std::string FormatStats(const char* name, const char* unit, const ErrorStats& s);
std::string StatsJson(const ErrorStats& s);
std::string JsonString(std::string_view s);

}  // namespace atlas::eval
