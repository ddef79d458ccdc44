#pragma once
// The one replay run of `atlas-replay` and `atlasd --replay`: the events of a log (a CARMEN log
// or an lcm-logger file, replay_source.h) through the same StepLoop as atlasd's live loop
// (odometry interpolated to each scan's stamp, core/mapper/step_loop.h), every scan or sonar
// reading the maps use (MapperSettings::sensors) stepped at once, and the output files of
// docs/formats.md ("Replay output"):
//   trajectory.tsv  timestamp frame x y theta            (dominant pose in its own frame)
//   graph.tsv       from to x y theta c00 c01 c02 c11 c12 c22 kind   (per edge, end of run)
//   timing.tsv      step timestamp frames hypotheses dominant step_ns
//   global.tsv      timestamp x y theta   (each trajectory pose composed with its frame's pose
//                   in the Dijkstra projection (paper, Section II-B) rooted at frame 0, taken at
//                   the END of the run; rows whose frame is unreachable are left out)
//   frames.tsv      frame step timestamp parent   (each frame's Genesis: the step whose scan
//                   its origin is the robot pose at, and the frame it was started from)
//   maps.tsv        frame line rho alpha x1 y1 x2 y2 c_rr c_ra c_aa   (every frame's lines, end)
//   points.tsv      frame x y   (the cells of laser points each frame keeps for map-matching,
//                   core/atlas/frame_points.h; a grid frame's occupied cells; none for the
//                   sonar atlas)
//   step_cpu.tsv    step cpu_ns   (the stepping thread's CPU time of each step)
//   summary.json    the figures of ReplaySummary
// With a reference trajectory (corrected logs: their corrected poses; simulated runs: truth):
//   reference.tsv   timestamp x y theta   (the reference pose at each stepped scan)
//   closures.tsv    each map-match edge against the reference (closure_check.h)
// With the hypotheses asked for (ReplayOptions::hypotheses):
//   hypotheses.tsv  step timestamp id frame state dominant steps q observations matched
//                   bootstrapped x y theta sx sy stheta   (every live hypothesis after each step:
//                   its pose in its own frame and the square roots of its covariance's diagonal)
// With a refiner given (offline, after the run; tools/replay/replay_refiner.h):
//   global_refined.tsv  timestamp x y theta   (as global.tsv, frames placed by least squares)
// Deterministic: the same events and settings give byte-identical files, except what is
// measured while stepping (step_ns in timing.tsv, step_cpu.tsv, the summary's time and memory
// figures); tests/replay/entry_points_identical.sh compares the two entry points.

#include <array>
#include <cstdint>
#include <functional>
#include <optional>
#include <string>
#include <vector>

#include "core/mapper/mapper_factory.h"
#include "core/mapper/step_loop.h"
#include "formats/trajectory_tsv.h"
#include "logs/carmen/carmen_log.h"
#include "replay/closure_check.h"

namespace atlas::replay {

struct ReplaySummary {
  int64_t scans = 0;           // stepped
  int64_t sonar_readings = 0;  // stepped (an LCM log recorded with the sonar)
  int64_t odometry_samples = 0;
  int64_t scans_without_odometry = 0;
  // Scan matching (scan_match.enabled): increments matched, and scans that fell back to the
  // odometry (StepLoop::scan_matches / scan_match_fallbacks).
  int64_t scan_matches = 0, scan_match_fallbacks = 0;
  int frames = 0;
  int edges = 0;
  int genesis_edges = 0, map_match_edges = 0, refined_edges = 0;  // by current kind
  int map_match_origin_edges = 0;  // edges first made by map-matching
  int64_t match_accepted = 0, match_rejected = 0, match_ambiguous = 0;
  // Accepted matches whose placement the frames' points chose (core/atlas/map_match.h, "Points").
  int64_t match_by_points = 0;
  // Steps whose input the atlas refused (StepStats::rejected_input).
  int64_t rejected_input = 0;
  // Map-matching outcomes by MapMatchReason (index static_cast<int>(reason)).
  std::array<int64_t, kMapMatchReasonCount> match_reasons{};
  // Traversal (III-E): juveniles seeded, matured, deleted (of which killed because w failed).
  int64_t seeded = 0, matured = 0, deleted = 0, killed_by_w = 0;
  // Edge refinement observations outside the gate, and mature hypotheses retired because they
  // contradicted the dominant one across an edge (core/atlas/atlas.h, steps 3 and 7).
  int64_t refine_rejected = 0, contradicting = 0;
  int global_rows = 0;        // trajectory rows placed in the global projection
  double data_seconds = 0.0;  // last scan stamp - first scan stamp
  double wall_seconds = 0.0;  // stepping only (not reading the log or writing files)
  double step_ns_median = 0.0, step_ns_max = 0.0;
  // The stepping thread's CPU time per step (CLOCK_THREAD_CPUTIME_ID): on a shared machine the
  // wall time above includes time the core was given to other processes.
  double step_cpu_ns_median = 0.0, step_cpu_ns_max = 0.0;
  int64_t overruns = 0;  // steps longer than the step loop's budget (wall time)
  double step_budget_ms = 0.0;
  // Memory (Linux): peak resident set of the process (getrusage), and the resident set just
  // before the first step and after the last (the difference is mostly the atlas).
  int64_t max_rss_kb = 0, rss_kb_before_steps = 0, rss_kb_after_steps = 0;
  // The size of the atlas's byte image (Atlas::Serialize: graph, maps, hypotheses) at the end.
  int64_t atlas_image_bytes = 0;
  // With restart_after_scans: the frame the robot restarted in (-1: no restart), and the scans
  // stepped after the restart until a map-matching edge joined the new part to the old frames
  // (-1: never).
  int restart_frame = -1;
  int64_t rejoined_after_scans = -1;
  // With a reference: closures (closure_check.h); -1 when there is no reference.
  int reference_rows = 0;
  int closures_checked = -1, false_closures_chi2 = -1, false_closures_axis = -1;
  int gross_closures = -1;
  // With refinement: frames placed, constraints, costs, status ("" when not asked for); the
  // solver's iterations (its log's length, the initial evaluation included), the frames not
  // connected to frame 0 and the edges whose covariance was not usable (both left out; see
  // RefineResult).
  std::string refine_status;
  int refined_frames = 0, refine_constraints = 0, refined_rows = 0;
  int refine_iterations = 0, refine_unreached_frames = 0, refine_skipped_edges = 0;
  double refine_initial_cost = 0.0, refine_final_cost = 0.0, refine_seconds = 0.0;
};

struct ReplaySummary;
// Global refinement of the finished atlas: each frame's pose in frame 0 (nullopt for frames it
// does not place); fills the summary's refine_* figures.
using Refiner = std::function<std::vector<std::optional<Pose2>>(const AtlasGraph& graph,
                                                                ReplaySummary* summary)>;

struct ReplayOptions {
  MapperSettings mapper;
  StepLoopOptions loop;
  int64_t max_scans = 0;  // 0: all
  // A restart after this many scans (0: none), as atlasd's resume does it: the atlas's image is
  // read back (Atlas::Deserialize) and the robot starts in a new, unconnected frame
  // (Atlas::ResumeInNewFrame), which map-matching without a prior may join to the old ones.
  int64_t restart_after_scans = 0;
  // A range setting applied to every scan before the loop (LimitLaserRange), metres; 0: each
  // scan's own maximum (the scanner's, as the log states it).
  double laser_max_range = 0.0;
  Refiner refine;           // set: write global_refined.tsv
  bool hypotheses = false;  // write hypotheses.tsv
  ClosureCheckOptions closures;
  std::string Validate() const;  // empty when valid
};

struct ReplayResult {
  std::string error;  // empty on success: "<what>: <why>"
  ReplaySummary summary;
  std::vector<formats::FramePoseRow> trajectory;  // the rows of trajectory.tsv
};

// Steps every scan (and sonar reading) of `events` (in log order) that the maps use and writes
// the files into `out_dir` (created if missing). `progress`, when set, is called about every
// `progress_every` scans with the number stepped so far. `reference` (optional, sorted by
// stamp) holds reference poses; those within 1 ms of a scan's stamp are that scan's reference.
ReplayResult RunReplay(const std::vector<SensorEvent>& events, const ReplayOptions& options,
                       const std::string& out_dir,
                       const std::function<void(int64_t done, int64_t total)>& progress = {},
                       int64_t progress_every = 1000,
                       const std::vector<TruthSample>& reference = {});
// The same for the events of a CARMEN log.
ReplayResult RunReplay(const std::vector<carmen::CarmenEvent>& events, const ReplayOptions& options,
                       const std::string& out_dir,
                       const std::function<void(int64_t done, int64_t total)>& progress = {},
                       int64_t progress_every = 1000,
                       const std::vector<TruthSample>& reference = {});

// The reference poses of a log read with reference_trajectory set (corrected logs): the poses
// of its laser lines, at their stamps.
std::vector<TruthSample> ReferenceAtScans(const carmen::CarmenLog& log);

// CPU time of the calling thread (CLOCK_THREAD_CPUTIME_ID), ns: a step's cost without the time
// other processes took the core.
int64_t ThreadCpuNs();

// Creates `dir` unless it exists; returns an error message ("cannot create DIR: why") or "".
std::string CreateOutputDir(const std::string& dir);

// Writes `text` to dir/name (formats::WriteTextFile); "" or "cannot write PATH: why".
std::string WriteOutputFile(const std::string& dir, const char* name, const std::string& text);

std::string SummaryJson(const ReplaySummary& s);
std::string SummaryText(const ReplaySummary& s);

}  // namespace atlas::replay
