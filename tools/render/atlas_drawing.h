#pragma once
// Pictures of an atlas (replay output, formats/replay_dir.h), as in the paper:
// - DrawAtlasProjection: the Dijkstra projection (Section III-A) from a chosen source frame:
//   every reached frame placed at its projected pose with its map's lines, its origin, the
//   n-sigma ellipse of its projected position covariance ("the accumulated projection error",
//   Fig. 2, Fig. 10), the projection tree's edges (solid) and the other edges (dashed);
//   optionally the global trajectory of the run (Fig. 8: the whole run). With refined poses
//   given, frames are placed there instead (no ellipses: the refinement has none).
// - DrawTimeline: step time and the dominant frame id over time (Fig. 7), or step time against
//   the number of frames (constant time).

#include <optional>
#include <string>
#include <vector>

#include "formats/replay_dir.h"
#include "tools/render/canvas.h"

namespace atlas::draw {

struct AtlasDrawOptions {
  int width_px = 1600;
  FrameId source = 0;
  bool ellipses = true;
  double n_sigma = 3.0;
  bool frame_labels = true;
  bool trajectory = false;  // draw the run's global trajectory (global.tsv, or refined)
  bool refined = false;     // place frames by global_refined poses (atlas-refine / --refine)
  std::string title;
};

// The frames' placement for a picture: projected (with covariance) or refined.
struct AtlasLayout {
  std::vector<std::optional<UncertainPose>> frame_pose;  // per frame id, in the source frame
  std::vector<int> tree_parent_edge;                     // -1: none (source or unreached)
  int reached = 0;
  Vec2 min = Vec2::Zero(), max = Vec2::Zero();
};

// Places the frames of `run` (projection from options.source, or the refined arrangement from
// `refined_frames`); returns "" or what is wrong (e.g. the source is not a frame).
std::string LayoutAtlas(const formats::ReplayOutput& run, const AtlasGraph& graph,
                        const AtlasDrawOptions& options,
                        const std::vector<std::optional<Pose2>>* refined_frames,
                        AtlasLayout* layout, int* height_px, ViewTransform* view);

void DrawAtlasProjection(Canvas& canvas, const formats::ReplayOutput& run, const AtlasGraph& graph,
                         const AtlasLayout& layout, const AtlasDrawOptions& options);

enum class TimelineAxis { kTime, kFrames };
struct TimelineOptions {
  int width_px = 1600;
  int height_px = 900;
  TimelineAxis axis = TimelineAxis::kTime;
  double budget_ms = 10.0;  // drawn as a line when within the plot
  std::string step_label = "step time (ms)";
  std::string title;
};
// Two panels: step time (ms; points, and a running median) and, against time, the dominant
// frame id with the frame count (Fig. 7); against the frame count, step time only.
void DrawTimeline(Canvas& canvas, const std::vector<formats::TimingRecord>& timing,
                  const TimelineOptions& options);

}  // namespace atlas::draw
