#pragma once
// Pose files, "timestamp x y theta" (docs/formats.md, "Pose file"): atlas-eval's trajectories,
// atlas-carmen's dumps, atlas-sim's truth.tsv (written row by row by sim::AppendTruthRow, which
// shares the CARMEN writer's number formatting), and global.tsv, global_refined.tsv and
// reference.tsv of a replay output directory.

#include <span>
#include <string>
#include <string_view>
#include <vector>

#include "core/eval/timed_trajectory.h"

namespace atlas::formats {

// The rows in file order. Stamps within kMaxAbsStampS, positions and angles within the limits
// of text_rows.h, theta wrapped to (-pi, pi]; two rows with the same stamp (to the nanosecond)
// are an error naming both lines. A file without rows is not an error here.
struct PoseRows {
  std::vector<eval::TimedPose> poses;
  std::vector<int64_t> lines;  // the line of each row
  std::string error;           // "<source>:<line>: <what>"; empty when valid
};
PoseRows ParsePoseRows(std::string_view text, const std::string& source);

// "# <comment>" (each line of `comment` a comment line), then one row per pose: seconds, metres
// and radians with 6 decimals, tab-separated.
std::string FormatPoseRows(std::span<const eval::TimedPose> poses, std::string_view comment);

// The first repeated stamp among `stamps` (with the lines they were read from), as
// "<source>:<line>: timestamp T repeats line L (...)"; "" when all differ.
std::string RepeatedStamp(std::vector<std::pair<Time, int64_t>> stamps, const std::string& source);

}  // namespace atlas::formats
