#pragma once
// Calibration of the laser time offset (StepLoopOptions::laser_time_offset,
// core/mapper/step_loop.h: a scan was taken at its stamp + offset) without ground truth, from
// the atlas's own heading corrections.
//
// Between two consecutive scans localised in the same map-frame the odometry predicts the
// heading change, and the scan update corrects it:
//   c = wrap( (theta_b - theta_a) - (odometry theta at t_b + offset - odometry theta at t_a +
//       offset) )
// with theta the dominant pose's heading in its frame (trajectory.tsv) and t the scan stamps.
// When the odometry is looked up at the wrong time, every turn is mispredicted by (turn rate x
// time error) and the filter must correct it scan after scan: the mean |c| over a run is
// smallest at the true offset (on mit-csail it falls from 1.63 deg at 0 to 1.15 deg at -0.12 s).
// Odometry noise and map errors add corrections that do not depend on the offset; they raise
// the floor but do not move the minimum. A run needs turns (a straight run has no signal).
//
// The corrections are taken against the odometry interpolated at t + offset from all samples.
// For offsets <= 0 that is the odometry the step loop used; for positive offsets the loop may
// have extrapolated past the samples known at the scan's arrival (step_loop.h), so c then
// includes the extrapolation's error too.
//
// SweepLaserTimeOffset() replays a log once per offset (RunReplay, into OUT/offset_<+0.100>/)
// and scores each; BestOffset() picks the smallest mean |c|, and the vertex of the parabola
// through it and its two neighbours as a finer estimate.

#include <functional>
#include <string>
#include <vector>

#include "replay/replay_run.h"

namespace atlas::replay {

struct HeadingCorrections {
  int pairs = 0;    // consecutive rows in one frame, scored
  int skipped = 0;  // such pairs whose odometry could not be interpolated (outside the samples)
  double mean_abs_rad = 0.0;
  double rms_rad = 0.0;
};

// `trajectory` in stepping order (trajectory.tsv rows); `odometry` in stamp order (samples out
// of order are ignored, as by the step loop's OdometryTrack).
HeadingCorrections MeasureHeadingCorrections(const std::vector<formats::FramePoseRow>& trajectory,
                                             const std::vector<OdometrySample>& odometry,
                                             Duration offset);

// FROM:TO:STEP in seconds, e.g. "-0.2:0:0.02".
struct OffsetRange {
  double from_s = -0.2, to_s = 0.0, step_s = 0.02;
  std::string Validate() const;  // empty when valid: within [-1, 1] s, at most 201 offsets
  std::vector<double> Offsets() const;
};
// Parses "FROM:TO:STEP"; on failure returns false with `error` saying what was wrong.
bool ParseOffsetRange(const std::string& text, OffsetRange* range, std::string* error);

struct OffsetSweepRow {
  double offset_s = 0.0;
  HeadingCorrections corrections;
  ReplaySummary summary;
};

struct SweepBest {
  int index = -1;           // row with the smallest mean |c|; -1 when no row has pairs
  double offset_s = 0.0;    // its offset
  bool has_vertex = false;  // the minimum is interior and the parabola opens upwards
  double vertex_s = 0.0;    // the parabola's vertex (uniform steps), within one step of offset_s
};
SweepBest BestOffset(const std::vector<OffsetSweepRow>& rows);

struct SweepResult {
  std::string error;  // empty on success
  std::vector<OffsetSweepRow> rows;
  SweepBest best;
};

// Replays `events` once per offset of `range` with `options` (its loop.laser_time_offset set to
// each), into out_dir/offset_<%+.3f>/, and writes out_dir/sweep.tsv (FormatSweep). `on_row`,
// when set, is called after each offset with the row and the count done so far.
SweepResult SweepLaserTimeOffset(
    const std::vector<carmen::CarmenEvent>& events, const ReplayOptions& options,
    const OffsetRange& range, const std::string& out_dir,
    const std::function<void(const OffsetSweepRow& row, int done, int total)>& on_row = {});

// "offset_s pairs mean_abs_deg rms_deg frames map_match_edges" rows with a header comment, and
// the best offset as a trailing comment.
std::string FormatSweep(const SweepResult& result);

}  // namespace atlas::replay
