#pragma once
// A replay output directory (docs/formats.md, "Replay output"), as `atlas-replay` and `atlasd
// --replay` write it, read back for atlas-eval, atlas-refine and atlas-render; and the writers of
// its maps.tsv and points.tsv (shared with `atlasd --export-atlas`). trajectory.tsv, graph.tsv
// and the pose files have their own headers (trajectory_tsv.h, graph_tsv.h, pose_file.h).
// Parsers take text and a source name for messages; ReadReplayOutput() reads the files.
//
// Every file is tab- or space-separated with '#' comment lines (text_rows.h); a data line with
// the wrong number of fields or a bad field is an error "<file>:<line>: <what>", never a crash.

#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "core/atlas/atlas_graph.h"
#include "core/eval/timed_trajectory.h"
#include "core/geometry/se2.h"
#include "formats/graph_tsv.h"
#include "formats/trajectory_tsv.h"

namespace atlas::formats {

struct TimingRecord {  // timing.tsv
  int64_t step = 0;
  double stamp_s = 0.0;
  int frames = 0;
  int hypotheses = 0;
  FrameId dominant = kNoFrame;
  int64_t step_ns = 0;
};
struct FrameRecord {  // frames.tsv
  FrameId frame = kNoFrame;
  int64_t step = 0;  // the atlas step whose scan the frame's origin is the robot pose at
  double stamp_s = 0.0;
  FrameId parent = kNoFrame;  // the frame Genesis started it from; kNoFrame for frame 0
};
struct FrameLine {  // maps.tsv
  FrameId frame = kNoFrame;
  MapLine line;
};
struct FramePointRow {  // points.tsv
  FrameId frame = kNoFrame;
  Vec2 p = Vec2::Zero();  // a cell centre in the frame's coordinates
};

struct ReplayOutput {
  std::vector<FramePoseRow> trajectory;
  GraphRows graph;
  std::vector<TimingRecord> timing;
  std::vector<FrameRecord> frames;       // empty if frames.tsv is absent (an exported atlas)
  std::vector<FrameLine> lines;          // empty if maps.tsv is absent
  std::vector<FramePointRow> points;     // empty if points.tsv is absent
  std::vector<eval::TimedPose> global;   // empty if global.tsv is absent
  std::vector<eval::TimedPose> refined;  // empty if global_refined.tsv is absent
  std::vector<int64_t> step_cpu_ns;      // step_cpu.tsv, by step - 1; empty if absent
  int frame_count = 0;                   // 1 + the largest frame id named anywhere
};

// Which files ReadReplayOutput must find (the others are read when present).
struct ReplayFilesWanted {
  bool trajectory = true;
  bool graph = true;
  bool timing = false;
  bool frames = false;
  bool maps = false;  // maps.tsv, and rows in it or in points.tsv (a map to draw)
  bool step_cpu = false;
};

std::string ParseTimingRows(std::string_view text, const std::string& source,
                            std::vector<TimingRecord>* out);
std::string ParseFrameRows(std::string_view text, const std::string& source,
                           std::vector<FrameRecord>* out);
std::string ParseMapRows(std::string_view text, const std::string& source,
                         std::vector<FrameLine>* out);
std::string ParsePointRows(std::string_view text, const std::string& source,
                           std::vector<FramePointRow>* out);

// Reads `dir`'s files; returns "" or what is wrong ("<dir>/graph.tsv: cannot open (...)").
// Beyond each row's syntax it checks that the files agree: a wanted trajectory.tsv, timing.tsv,
// maps.tsv (unless points.tsv has rows) or step_cpu.tsv without rows, a global.tsv or
// global_refined.tsv without rows next to a trajectory with rows, an empty graph.tsv for more
// than one frame, and (when frames.tsv or timing.tsv says how many frames the run made) an edge
// or trajectory row naming a frame beyond them are errors ("<dir>/graph.tsv:12: edge 0-99 names
// frame 99, but the run has 4 frames").
std::string ReadReplayOutput(const std::string& dir, const ReplayFilesWanted& wanted,
                             ReplayOutput* out);

// Each frame's pose in frame `source`, by the Dijkstra projection from it (paper, Section
// III-A); nullopt for frames it does not reach. Empty for a graph without frames; all nullopt
// when `source` is not a frame of the graph.
std::vector<std::optional<Pose2>> FramePosesFrom(const AtlasGraph& graph, FrameId source);
inline std::vector<std::optional<Pose2>> FramePosesFromFrameZero(const AtlasGraph& graph) {
  return FramePosesFrom(graph, 0);
}

// Each trajectory row composed with its frame's global pose; rows whose frame has no global
// pose are left out.
std::vector<eval::TimedPose> PlaceTrajectory(const std::vector<FramePoseRow>& trajectory,
                                             const std::vector<std::optional<Pose2>>& frame_pose);

// The text of global.tsv / global_refined.tsv: a pose file (pose_file.h) of the rows of
// PlaceTrajectory(). `rows_written` (optional) counts them.
std::string FormatGlobalTrajectory(const std::vector<FramePoseRow>& trajectory,
                                   const std::vector<std::optional<Pose2>>& frame_pose,
                                   const std::string& comment, int* rows_written = nullptr);

// The maps.tsv rows of every frame's lines: "frame line rho alpha x1 y1 x2 y2 c_rr c_ra c_aa".
std::string MapsTsvRows(const AtlasGraph& graph);
// The points.tsv rows of every frame's points: "frame x y", cell centres in the frame's
// coordinates. A frame's points are the laser points it keeps for map-matching
// (core/atlas/frame_points.h), or, when it keeps none, its map's own (LocalMap::Points: a grid
// frame's occupied cells), at most kMaxMapPointsPerFrame of them, evenly subsampled.
inline constexpr int kMaxMapPointsPerFrame = 2048;  // frame_points.capacity's default
std::string PointsTsvRows(const AtlasGraph& graph);

}  // namespace atlas::formats
