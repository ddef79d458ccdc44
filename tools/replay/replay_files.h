#pragma once
// Reading atlas-replay's output directory back (docs/formats.md, "atlas-replay output"), for
// atlas-refine and atlas-render. Parsers take text and a source name for messages;
// ReadReplayOutput() is the only function here that touches the file system.
//
// Every file is tab- or space-separated with '#' comment lines; a data line with the wrong
// number of fields or a field that is not a finite number is an error
// "<file>:<line>: <what>", never a crash.

#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "core/atlas/atlas_graph.h"
#include "core/geometry/se2.h"

namespace atlas::replay {

struct StampedFramePose {  // trajectory.tsv
  double stamp_s = 0.0;
  FrameId frame = kNoFrame;
  Pose2 pose;
  int64_t line = 0;  // in trajectory.tsv (0: not read from a file)
};
struct EdgeRecord {  // graph.tsv
  FrameId a = kNoFrame, b = kNoFrame;
  UncertainPose b_in_a;
  std::string kind;  // genesis | map-match | refined
  int64_t line = 0;  // in graph.tsv (0: not read from a file)
};
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
struct StampedPose {  // global.tsv, global_refined.tsv
  double stamp_s = 0.0;
  Pose2 pose;
};

struct ReplayOutput {
  std::vector<StampedFramePose> trajectory;
  std::vector<EdgeRecord> edges;
  std::vector<TimingRecord> timing;
  std::vector<FrameRecord> frames;    // empty if frames.tsv is absent (older runs)
  std::vector<FrameLine> lines;       // empty if maps.tsv is absent
  std::vector<FramePointRow> points;  // empty if points.tsv is absent
  std::vector<StampedPose> global;    // empty if global.tsv is absent
  std::vector<StampedPose> refined;   // empty if global_refined.tsv is absent
  std::vector<int64_t> step_cpu_ns;   // step_cpu.tsv, by step - 1; empty if absent
  int frame_count = 0;                // 1 + the largest frame id named anywhere
};

// Which files ReadReplayOutput must find (the others are read when present).
struct ReplayFilesWanted {
  bool trajectory = true;
  bool graph = true;
  bool timing = false;
  bool frames = false;
  bool maps = false;
  bool step_cpu = false;
};

std::string ParseTrajectoryRows(std::string_view text, const std::string& source,
                                std::vector<StampedFramePose>* out);
std::string ParseEdgeRows(std::string_view text, const std::string& source,
                          std::vector<EdgeRecord>* out);
std::string ParseTimingRows(std::string_view text, const std::string& source,
                            std::vector<TimingRecord>* out);
std::string ParseFrameRows(std::string_view text, const std::string& source,
                           std::vector<FrameRecord>* out);
std::string ParseMapRows(std::string_view text, const std::string& source,
                         std::vector<FrameLine>* out);
std::string ParseStampedPoses(std::string_view text, const std::string& source,
                              std::vector<StampedPose>* out);
std::string ParsePointRows(std::string_view text, const std::string& source,
                           std::vector<FramePointRow>* out);

// Reads `dir`'s files; returns "" or what is wrong ("<dir>/graph.tsv: cannot open: ...").
// Beyond each row's syntax it checks that the files agree: a wanted trajectory.tsv, timing.tsv,
// maps.tsv or step_cpu.tsv without rows, a global.tsv or global_refined.tsv without rows next
// to a trajectory with rows, an empty graph.tsv for more than one frame, and (when frames.tsv or
// timing.tsv says how many frames the run made) an edge or trajectory row naming a frame beyond
// them are errors ("<dir>/graph.tsv:12: edge 0-99 names frame 99, but the run has 4 frames").
// graph.tsv covariances must be positive definite.
std::string ReadReplayOutput(const std::string& dir, const ReplayFilesWanted& wanted,
                             ReplayOutput* out);

// An atlas graph with `frame_count` frames (no maps) and the given edges, for the Dijkstra
// projection and global refinement of a finished run. Edges naming frames outside
// [0, frame_count), joining a frame to itself or repeating a pair are an error.
struct GraphFromEdges {
  AtlasGraph graph;
  std::string error;
  std::string where;  // ":LINE" of the offending graph.tsv row when known, else empty
};
GraphFromEdges BuildGraph(const std::vector<EdgeRecord>& edges, int frame_count);

// Each frame's pose in frame 0, by the Dijkstra projection from frame 0 (paper, Section III-A);
// nullopt for frames it does not reach. Empty for a graph without frames.
std::vector<std::optional<Pose2>> FramePosesFromFrameZero(const AtlasGraph& graph);

// Each trajectory row composed with its frame's global pose; rows whose frame has no global
// pose are left out.
std::vector<StampedPose> PlaceTrajectory(const std::vector<StampedFramePose>& trajectory,
                                         const std::vector<std::optional<Pose2>>& frame_pose);

// The text of global.tsv / global_refined.tsv: a "# comment" line, then the rows of
// PlaceTrajectory(), "timestamp x y theta" (6 decimals). `rows_written` (optional) counts them.
std::string FormatGlobalTrajectory(const std::vector<StampedFramePose>& trajectory,
                                   const std::vector<std::optional<Pose2>>& frame_pose,
                                   const std::string& comment, int* rows_written = nullptr);

// The kind written in graph.tsv back to the enum; false for an unknown name.
bool EdgeKindFromName(std::string_view name, EdgeKind* kind);

}  // namespace atlas::replay
