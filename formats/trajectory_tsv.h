#pragma once
// trajectory.tsv of a replay output directory (docs/formats.md, "Replay output"): one row per
// stepped scan with a dominant hypothesis, "timestamp frame x y theta", the robot's pose in the
// coordinates of its map-frame.

#include <span>
#include <string>
#include <string_view>
#include <vector>

#include "core/atlas/atlas_graph.h"
#include "core/common/time.h"

namespace atlas::formats {

struct FramePoseRow {
  Time stamp{};
  FrameId frame = kNoFrame;
  Pose2 pose;
  int64_t line = 0;  // in trajectory.tsv (0: not read from a file)
};

// Appends the rows of `text` to `out`; "" or "<source>:<line>: <what>". The stamp, pose and
// frame fields follow text_rows.h (theta wrapped to (-pi, pi]); two rows with the same stamp
// are an error naming both lines.
std::string ParseTrajectoryTsv(std::string_view text, const std::string& source,
                               std::vector<FramePoseRow>* out);

// The file: the header line "# <comment>", then the rows (seconds, metres and radians with 6
// decimals, tab-separated).
std::string FormatTrajectoryTsv(std::span<const FramePoseRow> rows, std::string_view comment);

}  // namespace atlas::formats
