// atlas-replay: runs a CARMEN log through the Atlas as fast as it can. See --help.

#include <sys/stat.h>
#include <unistd.h>

#include <chrono>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <limits>
#include <optional>
#include <string>

#include "core/common/version.h"
#include "formats/config/config_loader.h"
#include "formats/config/mapper_config.h"
#include "formats/pose_file.h"
#include "formats/text_rows.h"
#include "replay/laser_time_offset.h"
#include "replay/replay_run.h"
#include "replay/replay_source.h"
#include "sim/reference_odometry.h"
#include "tools/cli/carmen_log_options.h"
#include "tools/cli/command_line.h"
#include "tools/cli/odometry_noise_options.h"
#include "tools/replay/progress.h"
#include "tools/replay/replay_refiner.h"

namespace atlas::replay {
namespace {

constexpr const char* kDescription =
    R"(Runs a CARMEN log (plain or gzip; ODOM and laser lines), or an lcm-logger file with atlasd's
raw channels (lcm.channels.raw_*, from --config), through the Atlas as fast as it can, with
atlasd's step loop (odometry interpolated to each scan's stamp, every scan stepped). `atlasd
--replay LOG --out DIR --config FILE` is the same replay: it writes the same files.
SIMDIR, an atlas-sim output directory, stands for SIMDIR/run.clf (its truth only with --reference).
Writes into --out DIR (docs/formats.md, "Replay output"):
  trajectory.tsv   timestamp frame x y theta   (dominant hypothesis's pose in its own frame)
  graph.tsv        from to x y theta c00 c01 c02 c11 c12 c22 kind   (one row per edge)
  timing.tsv       step timestamp frames hypotheses dominant step_ns
  global.tsv       timestamp x y theta   (Dijkstra projection from frame 0, end of run)
  frames.tsv       frame step timestamp parent   (each frame's Genesis)
  maps.tsv         frame line rho alpha x1 y1 x2 y2 c_rr c_ra c_aa   (every frame's lines)
  points.tsv       frame x y   (the laser points each frame keeps for map-matching, 10 cm cells;
                   grid frames: their occupied cells, 5 cm)
  summary.json     the summary printed on stdout
  reference.tsv, closures.tsv   with --corrected: the reference pose at each scan, and every
                   map-match edge against the reference (false loop closures)
  global_refined.tsv   with --refine: as global.tsv, frames placed by least squares (Ceres)
  hypotheses.tsv   with --hypotheses: step timestamp id frame state dominant steps q
                   observations matched bootstrapped x y theta sx sy stheta   (every live
                   hypothesis after each step, its pose in its own frame)
Score global.tsv with: atlas-eval --relations FILE.relations DIR/global.tsv
                  or:  atlas-eval --reference DIR/reference.tsv DIR/global.tsv)";

constexpr const char* kFooter =
    R"(Exit status: 0 done, 1 the log could not be read or the output not written (or a sweep scored
no pair of scans), 2 bad command line,
78 the --config file was rejected (each error with its key, line and column).
)";

int Sweep(const std::vector<carmen::CarmenEvent>& events, const ReplayOptions& options,
          const OffsetRange& range, const std::string& out_dir, bool quiet,
          const std::string& log_path) {
  const auto start = std::chrono::steady_clock::now();
  const SweepResult s = SweepLaserTimeOffset(
      events, options, range, out_dir, [&](const OffsetSweepRow& row, int done, int total) {
        if (quiet) return;
        std::fprintf(
            stderr,
            "atlas-replay: offset %+.3f s (%d/%d): mean |heading correction| %.3f deg, "
            "%d pairs, %.1f s\n",
            row.offset_s, done, total, row.corrections.mean_abs_rad * 180.0 / M_PI,
            row.corrections.pairs,
            std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count());
      });
  if (!s.error.empty()) {
    std::fprintf(stderr, "atlas-replay: %s\n", s.error.c_str());
    return 1;
  }
  std::printf("atlas-replay laser time offset sweep %s -> %s/sweep.tsv\n%s", log_path.c_str(),
              out_dir.c_str(), FormatSweep(s).c_str());
  return s.best.index < 0 ? 1 : 0;
}

int Main(int argc, char** argv) {
  std::string log_path, out_dir = "replay-out", config_path;
  ReplayOptions options;
  carmen::CarmenLogOptions log_options;
  WheelOdometryNoiseOptions noise;
  uint64_t seed = 1;
  std::string reference_path;
  bool quiet = false, corrected = false, sweep = false, refine = false;
  OffsetRange sweep_range;
  // What the command line sets over the --config file's values.
  std::optional<double> laser_time_offset_s;
  int map_capacity = 0, max_hypotheses = 0;  // 0: not given

  cli::CommandLine command_line(
      "atlas-replay",
      {"atlas-replay [options] LOG", "atlas-replay [options] SIMDIR",
       "atlas-replay --sweep-laser-time-offset FROM:TO:STEP [options] LOG|SIMDIR"},
      kDescription, std::string(kFooter) + kOdometryNoiseHelp);
  CLI::App& app = command_line.app();
  cli::AddPositional(app, "LOG", &log_path, "the log (or SIMDIR) to replay");
  cli::AddText(app, "-o,--out", "DIR", &out_dir,
               "output directory, created if missing (default: replay-out)");
  cli::AddFlag(app, "--refine", &refine,
               "also arrange all frames by global least squares after the run (offline;\n"
               "never in the step loop) and write global_refined.tsv");
  cli::AddFlag(app, "--hypotheses", &options.hypotheses,
               "also write hypotheses.tsv: which hypotheses were alive at each step,\n"
               "in which frame, juvenile or mature, with their q (Section III-B, III-E)");
  cli::AddText(app, "--reference", "FILE", &reference_path,
               "a trajectory file (atlas-sim's truth.tsv) whose poses within 1 ms of a\n"
               "scan are its reference: writes reference.tsv and closures.tsv as\n"
               "--corrected does (not with --corrected)");
  cli::AddInteger(app, "--max-scans", "N", 1, std::numeric_limits<int64_t>::max(),
                  &options.max_scans, "step only the first N scans (default: all)");
  cli::AddInteger(app, "--restart-after-scans", "N", 1, std::numeric_limits<int64_t>::max(),
                  &options.restart_after_scans,
                  "restart after N scans as atlasd resumes a saved atlas: the robot goes on\n"
                  "in a new frame, unconnected, until map-matching without a prior joins\n"
                  "it to the old frames (summary.json: restart_frame, rejoined_after_scans)");
  cli::AddText(app, "--config", "FILE", &config_path,
               "atlasd's configuration file: the mapper ([atlas], [noise.*]) and the\n"
               "step loop ([loop]) are taken from it, so that the replay maps as\n"
               "atlasd would (devices, LCM and state are ignored: the scans' ranges\n"
               "are the log's, not laser.max_range_m's);\n"
               "the options below override it. Without it: the defaults shown below\n"
               "and core/localmap's noise models");
  cli::AddNumber(
      app, "--laser-max-range", "M", 0.01, 1e6, [&](double m) { options.laser_max_range = m; },
      "a range setting for the scanner: returns at or beyond M metres are no\n"
      "return (default: each scan's own maximum, as the log states it)");
  cli::AddNumber(
      app, "--laser-time-offset", "S", -1, 1, [&](double s) { laser_time_offset_s = s; },
      "a scan was taken at its stamp + S seconds (-1..1; negative: before\n"
      "the stamp; default 0 or the config's laser.time_offset_s): the odometry\n"
      "is looked up there; trajectory rows keep the scan stamps. mit-csail\n"
      "(361 beams at 38400 baud, stamped at arrival): about -0.1");
  cli::AddValue(
      app, "--sweep-laser-time-offset", "FROM:TO:STEP",
      [&](const std::string& v) {
        std::string error;
        if (!ParseOffsetRange(v, &sweep_range, &error))
          return "--sweep-laser-time-offset: " + error;
        sweep = true;
        return std::string();
      },
      "calibrate the offset without ground truth: replay once per offset\n"
      "(into OUT/offset_<S>/) and print, per offset, the mean and rms |heading\n"
      "correction| of the atlas between consecutive scans in one frame (the\n"
      "atlas's heading change minus the odometry's, odometry at stamp + offset);\n"
      "the smallest mean is the best offset (also OUT/sweep.tsv). Needs a run\n"
      "with turns. Example: --sweep-laser-time-offset -0.2:0:0.02");
  cli::AddInteger(app, "--map-capacity", "N", 1, 10000, &map_capacity,
                  "features per map-frame (default " +
                      std::to_string(MapperSettings{}.local_map.capacity) + ")");
  cli::AddInteger(
      app, "--max-hypotheses", "N", 1, 1000, &max_hypotheses,
      "live hypotheses (default " + std::to_string(MapperSettings{}.atlas.max_hypotheses) + ")");
  cli::AddFlag(app, "--quiet", &quiet, "no progress on stderr");
  const std::string log_group = "Reading the log";
  cli::AddCarmenLogOptions(app, log_group, &log_options, &corrected);
  const std::string noise_group = "Synthesised odometry (with --corrected)";
  cli::AddSeed(app, "--seed", &seed, "random seed (default 1)").Group(noise_group);
  cli::AddOdometryNoiseOptions(app, noise_group, &noise);
  if (std::optional<int> done = command_line.Parse(argc, argv)) return *done;
  LcmChannels channels;  // of an lcm-logger file: the configuration's raw channels
  if (!config_path.empty()) {
    const ConfigResult config = LoadConfigFile(config_path, ValidateMapperOptions);
    if (!config.ok()) {
      std::fprintf(stderr, "atlas-replay: configuration rejected:\n");
      for (const ConfigError& e : config.errors)
        std::fprintf(stderr, "  %s\n", e.ToString().c_str());
      return kExitConfigError;
    }
    options.mapper = ToMapperSettings(config.options);
    options.loop = ToStepLoopOptions(config.options);
    channels = config.options.lcm.channels;
  }
  if (laser_time_offset_s)
    options.loop.laser_time_offset = FromSeconds(*laser_time_offset_s).time_since_epoch();
  if (map_capacity > 0) options.mapper.local_map.capacity = map_capacity;
  if (max_hypotheses > 0) options.mapper.atlas.max_hypotheses = max_hypotheses;
  if (refine) options.refine = MakeRefiner(refine::RefineOptions{});
  auto Usage = [&](const std::string& what) { return command_line.Usage(what); };
  if (log_path.empty()) return Usage("no LOG given");
  if (corrected && !reference_path.empty())
    return Usage("--reference and --corrected both give the reference: give one");
  if (std::string e = options.Validate(); !e.empty()) return Usage(e);
  if (corrected) {
    log_options.clock = carmen::Clock::kLineOrder;
    log_options.reference_trajectory = true;
  }
  if (std::string e = log_options.Validate(); !e.empty()) return Usage(e);
  if (std::string e = noise.Validate(); !e.empty()) return Usage(e);
  struct stat st {};
  if (stat(log_path.c_str(), &st) == 0 && S_ISDIR(st.st_mode)) log_path += "/run.clf";

  if (!quiet) std::fprintf(stderr, "atlas-replay: reading %s\n", log_path.c_str());
  ProgressMeter meter(quiet ? nullptr : stderr, "atlas-replay", isatty(STDERR_FILENO) != 0);
  meter.Begin("reading", "MB", 1e6);
  const ReplaySource source = ReadReplaySource(
      log_path, log_options, RawChannels(channels), [&](int64_t done, int64_t total) {
        meter.Update(static_cast<double>(done), static_cast<double>(total));
      });
  meter.Finish();
  if (!source.error.empty()) {
    std::fprintf(stderr, "atlas-replay: %s\n", source.error.c_str());
    return 1;
  }
  if (source.lcm && (corrected || sweep))
    return Usage("--corrected and --sweep-laser-time-offset need a CARMEN log");
  if (!source.lcm && source.carmen.laser_events == 0) {
    std::fprintf(stderr, "atlas-replay: %s has no laser scans; nothing to replay\n",
                 log_path.c_str());
    return 1;
  }
  auto progress = [&](int64_t done, int64_t total) {
    meter.Update(static_cast<double>(done), static_cast<double>(total));
  };
  std::vector<TruthSample> reference;
  std::vector<carmen::CarmenEvent> synthesized;
  if (corrected) {
    if (source.carmen.reference.empty()) {
      std::fprintf(stderr, "atlas-replay: %s has no poses to use as the reference (--corrected)\n",
                   log_path.c_str());
      return 1;
    }
    reference = ReferenceAtScans(source.carmen);
    synthesized = carmen::EventsWithSynthesizedOdometry(source.carmen, noise, seed);
  }
  if (!reference_path.empty()) {
    const formats::TextFile file = formats::ReadTextFile(reference_path);
    if (!file.error.empty()) {
      std::fprintf(stderr, "atlas-replay: %s\n", file.error.c_str());
      return 1;
    }
    const formats::PoseRows parsed = formats::ParsePoseRows(file.text, reference_path);
    if (!parsed.error.empty()) {
      std::fprintf(stderr, "atlas-replay: %s\n", parsed.error.c_str());
      return 1;
    }
    for (const eval::TimedPose& p : parsed.poses) reference.push_back(TruthSample{p.stamp, p.pose});
  }
  if (sweep)
    return Sweep(corrected ? synthesized : source.carmen.events, options, sweep_range, out_dir,
                 quiet, log_path);
  // Called every 50 scans; the meter prints when due.
  meter.Begin("replaying", "scans", 1);
  ReplayResult r = corrected || !reference.empty()
                       ? RunReplay(corrected ? synthesized : source.carmen.events, options, out_dir,
                                   progress, 50, reference)
                       : RunReplay(source.events, options, out_dir, progress, 50);
  meter.Update(static_cast<double>(r.summary.scans), static_cast<double>(r.summary.scans));
  meter.Finish();
  if (!r.error.empty()) {
    std::fprintf(stderr, "atlas-replay: %s\n", r.error.c_str());
    return 1;
  }
  std::printf("atlas-replay %s -> %s\n%s", log_path.c_str(), out_dir.c_str(),
              SummaryText(r.summary).c_str());
  return ReplayVerdict(log_path, source, r, "atlas-replay");
}

}  // namespace
}  // namespace atlas::replay

int main(int argc, char** argv) { return atlas::replay::Main(argc, argv); }
