#pragma once
// atlas-replay's run: the events of a CARMEN log through the same StepLoop as atlasd (odometry
// interpolated to each scan's stamp, daemon/atlasd/step_loop.h), every scan stepped at once,
// and the output files of docs/formats.md ("atlas-replay output"):
//   trajectory.tsv  timestamp frame x y theta            (dominant pose in its own frame)
//   graph.tsv       from to x y theta c00 c01 c02 c11 c12 c22 kind   (per edge, end of run)
//   timing.tsv      step timestamp frames hypotheses dominant step_ns
//   global.tsv      timestamp x y theta   (each trajectory pose composed with its frame's pose
//                   in the Dijkstra projection (paper, Section II-B) rooted at frame 0, taken at
//                   the END of the run; rows whose frame is unreachable are left out)
//   summary.json    the figures of ReplaySummary
// Deterministic: the same events and settings give byte-identical files, except step_ns in
// timing.tsv and the wall-clock figures of the summary.

#include <cstdint>
#include <functional>
#include <string>
#include <vector>

#include "daemon/atlasd/atlas_factory.h"
#include "daemon/atlasd/step_loop.h"
#include "drivers/carmen/carmen_log.h"

namespace atlas::replay {

struct ReplayOptions {
  MapperSettings mapper;
  StepLoopOptions loop;
  int64_t max_scans = 0;         // 0: all
  std::string Validate() const;  // empty when valid
};

struct ReplaySummary {
  int64_t scans = 0;  // stepped
  int64_t odometry_samples = 0;
  int64_t scans_without_odometry = 0;
  int frames = 0;
  int edges = 0;
  int genesis_edges = 0, map_match_edges = 0, refined_edges = 0;  // by current kind
  int map_match_origin_edges = 0;  // edges first made by map-matching
  int64_t match_accepted = 0, match_rejected = 0, match_ambiguous = 0;
  int global_rows = 0;        // trajectory rows placed in the global projection
  double data_seconds = 0.0;  // last scan stamp - first scan stamp
  double wall_seconds = 0.0;  // stepping only (not reading the log or writing files)
  double step_ns_median = 0.0, step_ns_max = 0.0;
};

struct ReplayResult {
  std::string error;  // empty on success: "<what>: <why>"
  ReplaySummary summary;
};

// Steps every scan of `events` (time-ordered) and writes the files into `out_dir` (created if
// missing). `progress`, when set, is called about every `progress_every` scans with the number
// stepped so far.
ReplayResult RunReplay(const std::vector<carmen::CarmenEvent>& events, const ReplayOptions& options,
                       const std::string& out_dir,
                       const std::function<void(int64_t done, int64_t total)>& progress = {},
                       int64_t progress_every = 1000);

std::string SummaryJson(const ReplaySummary& s);
std::string SummaryText(const ReplaySummary& s);

}  // namespace atlas::replay
