#pragma once
// The text files of atlas-eval and atlas-carmen (docs/formats.md), and trajectories derived
// from CARMEN logs. Parsers take text and a source name for messages; ReadTextFile() is the
// only function here that touches the file system.
//
//   trajectory file   one pose per line: "timestamp x y theta" (seconds, metres, radians),
//                     separated by spaces or tabs; '#' comments and blank lines ignored.
//   relations file    Freiburg SLAM benchmark: "t1 t2 x y z roll pitch yaw", the pose at t2 in
//                     the frame of the pose at t1 (z, roll and pitch are ignored).

#include <map>
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

struct TextFile {
  std::string text;
  std::string error;  // empty when read
};
// Reads a whole file, plain or gzip-compressed.
TextFile ReadTextFile(const std::string& path);

// Limits on values read from the files: a stamp beyond 4e9 s overflows the nanosecond clock,
// and positions beyond 10,000 km or angles beyond 1000 rad are damage, not data.
inline constexpr double kMaxAbsStampS = 4e9;
inline constexpr double kMaxAbsPositionM = 1e7;
inline constexpr double kMaxAbsAngleRad = 1e3;

// Trajectory files: values out of the limits above, and two rows with the same stamp, are errors
// naming the line; rows need not be in time order (they are sorted).
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

// atlas-replay output (docs/formats.md): trajectory.tsv "timestamp frame x y theta" and
// graph.tsv "from to x y theta c00 c01 c02 c11 c12 c22 kind".
struct FramePosesParse {
  std::vector<FramePose> rows;
  std::vector<size_t> lines;  // the line of each row
  std::string error;
};
FramePosesParse ParseFrameTrajectory(std::string_view text, const std::string& source);
// An edge whose covariance is not positive definite (core/geometry/covariance.h), that joins a
// frame to itself or repeats a pair is an error naming the line.
struct EdgeRowsParse {
  std::vector<EdgeRow> rows;
  std::vector<size_t> lines;  // the line of each row
  int frame_count = 0;        // 1 + the largest frame id named
  std::string error;
};
EdgeRowsParse ParseGraphEdges(std::string_view text, const std::string& source);
// atlas-replay's frames.tsv ("frame step timestamp parent"): the number of frames the run made
// (1 + the largest frame id), or -1 with `error` set.
int64_t ParseFrameCount(std::string_view text, const std::string& source, std::string* error);
// The two files agree: with `frame_count` >= 0 (from frames.tsv, named `count_source`), no edge
// or trajectory row names a frame beyond it; an empty graph is an error for more than one frame.
// "" or "<file>:<line>: <what>".
std::string CheckFramesExist(const FramePosesParse& trajectory,
                             const std::string& trajectory_source, const EdgeRowsParse& edges,
                             const std::string& graph_source, int64_t frame_count,
                             const std::string& count_source);

// "timestamp x y theta" lines with a header comment; timestamps to the microsecond.
std::string FormatTrajectory(const TimedTrajectory& trajectory, const std::string& comment);

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
