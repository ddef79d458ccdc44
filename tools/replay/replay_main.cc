// atlas-replay: runs a CARMEN log through the Atlas as fast as it can. See --help.

#include <sys/stat.h>
#include <unistd.h>

#include <chrono>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <limits>
#include <string>

#include "core/common/parse_number.h"
#include "formats/config/config_loader.h"
#include "formats/config/mapper_config.h"
#include "formats/pose_file.h"
#include "formats/text_rows.h"
#include "replay/laser_time_offset.h"
#include "replay/replay_run.h"
#include "replay/replay_source.h"
#include "sim/reference_odometry.h"
#include "tools/replay/replay_refiner.h"

namespace atlas::replay {
namespace {

constexpr const char* kHelp = R"(Usage: atlas-replay [options] LOG
       atlas-replay [options] SIMDIR
       atlas-replay --sweep-laser-time-offset FROM:TO:STEP [options] LOG|SIMDIR

Runs a CARMEN log (plain or gzip; ODOM and laser lines), or an lcm-logger file with atlasd's
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
  points.tsv       frame x y   (the laser points each frame keeps for map-matching, 10 cm cells)
  summary.json     the summary printed on stdout
  reference.tsv, closures.tsv   with --corrected: the reference pose at each scan, and every
                   map-match edge against the reference (false loop closures)
  global_refined.tsv   with --refine: as global.tsv, frames placed by least squares (Ceres)
  hypotheses.tsv   with --hypotheses: step timestamp id frame state dominant steps q
                   observations matched bootstrapped x y theta sx sy stheta   (every live
                   hypothesis after each step, its pose in its own frame)
Score global.tsv with: atlas-eval --relations FILE.relations DIR/global.tsv
                  or:  atlas-eval --reference DIR/reference.tsv DIR/global.tsv

Options:
  --out DIR            output directory, created if missing (default: replay-out)
  --refine             also arrange all frames by global least squares after the run (offline;
                       never in the step loop) and write global_refined.tsv
  --hypotheses         also write hypotheses.tsv: which hypotheses were alive at each step,
                       in which frame, juvenile or mature, with their q (Section III-B, III-E)
  --corrected          a Radish "corrected" log: line order is the clock, its poses are the
                       reference; wheel odometry is synthesised from them with seeded noise:
    --seed N             random seed (default 1)
    --odometry-noise LEVEL  default | realistic (below)
    --wheel-noise V      wheel distance variance per metre rolled, m^2/m (default 5e-6)
    --left-scale E       left wheel radius error, relative (default 0.0002)
    --right-scale E      right wheel radius error, relative (default -0.0002)
    --track-width-error E  relative track width error (default 0.002)
    --line-period S      seconds per line for the line-order clock (default 0.05)
  --reference FILE     a trajectory file (atlas-sim's truth.tsv) whose poses within 1 ms of a
                       scan are its reference: writes reference.tsv and closures.tsv as
                       --corrected does (not with --corrected)
  --log-max-range M    ranges >= M metres in the log are no-return (aces-corrected: 50)
  --max-scans N        step only the first N scans (default: all)
  --config FILE        atlasd's configuration file: the mapper ([atlas], [noise.*], laser
                       max_range_m) and the step loop ([loop]) are taken from it, so that
                       the replay maps as atlasd would (devices, LCM and state are ignored);
                       the options below override it. Without it: the defaults shown below
                       and core/localmap's noise models
  --max-range M        ranges beyond M metres are no-return for the maps (default 8)
  --laser-time-offset S  a scan was taken at its stamp + S seconds (-1..1; negative: before
                       the stamp; default 0 or the config's laser.time_offset_s): the odometry
                       is looked up there; trajectory rows keep the scan stamps. mit-csail
                       (361 beams at 38400 baud, stamped at arrival): about -0.1
  --sweep-laser-time-offset FROM:TO:STEP
                       calibrate the offset without ground truth: replay once per offset
                       (into OUT/offset_<S>/) and print, per offset, the mean and rms |heading
                       correction| of the atlas between consecutive scans in one frame (the
                       atlas's heading change minus the odometry's, odometry at stamp + offset);
                       the smallest mean is the best offset (also OUT/sweep.tsv). Needs a run
                       with turns. Example: --sweep-laser-time-offset -0.2:0:0.02
  --map-capacity N     features per map-frame (default 10)
  --max-hypotheses N   live hypotheses (default 4)
  --skip-bad-lines     count malformed log lines instead of stopping at the first
  --quiet              no progress on stderr
  -h, --help           this text

Exit status: 0 done, 1 the log could not be read or the output not written (or a sweep scored
no pair of scans), 2 bad command line,
78 the --config file was rejected (each error with its key, line and column).
)";

int Usage(const std::string& what) {
  std::fprintf(stderr, "atlas-replay: %s\nTry 'atlas-replay --help'.\n", what.c_str());
  return 2;
}

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
  std::string log_path, out_dir = "replay-out";
  ReplayOptions options;
  carmen::CarmenLogOptions log_options;
  WheelOdometryNoiseOptions noise;
  uint64_t seed = 1;
  std::string reference_path;
  bool quiet = false, corrected = false, sweep = false;
  OffsetRange sweep_range;
  LcmChannels channels;  // of an lcm-logger file: the configuration's raw channels
  // --config first, so that the other options override what it sets.
  for (int i = 1; i + 1 < argc; ++i) {
    if (std::string(argv[i]) != "--config") continue;
    const ConfigResult config = LoadConfigFile(argv[i + 1], ValidateMapperOptions);
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
  for (int i = 1; i < argc; ++i) {
    const std::string a = argv[i];
    auto value = [&]() -> const char* { return i + 1 < argc ? argv[++i] : nullptr; };
    std::string error;
    // The next argument as a number (an integer, a seed) into `out`; false with `error` set.
    auto number = [&](double lo, double hi, double& out) {
      const char* v = value();
      if (v == nullptr) error = a + " needs a value";
      return v != nullptr && NumberArgument(a, v, lo, hi, out, error);
    };
    auto integer = [&](int64_t lo, int64_t hi, auto& out) {
      const char* v = value();
      if (v == nullptr) error = a + " needs a value";
      return v != nullptr && IntegerArgument(a, v, lo, hi, out, error);
    };
    if (a == "-h" || a == "--help") {
      std::fputs(kHelp, stdout);
      std::fputs(kOdometryNoiseHelp, stdout);
      return 0;
    } else if (a == "--out") {
      const char* v = value();
      if (v == nullptr || *v == '\0') return Usage("--out needs a directory");
      out_dir = v;
    } else if (a == "--config") {
      if (value() == nullptr) return Usage("--config needs a file");
    } else if (a == "--max-scans") {
      if (!integer(1, std::numeric_limits<int64_t>::max(), options.max_scans)) return Usage(error);
    } else if (a == "--max-range") {
      if (!number(0.01, 1e6, options.loop.max_range_m)) return Usage(error);
    } else if (a == "--map-capacity") {
      if (!integer(1, 10000, options.mapper.map_capacity)) return Usage(error);
    } else if (a == "--max-hypotheses") {
      if (!integer(1, 1000, options.mapper.max_hypotheses)) return Usage(error);
    } else if (a == "--laser-time-offset") {
      double d = 0.0;
      if (!number(-1, 1, d)) return Usage(error);
      options.loop.laser_time_offset = FromSeconds(d).time_since_epoch();
    } else if (a == "--sweep-laser-time-offset") {
      const char* v = value();
      if (v == nullptr) return Usage("--sweep-laser-time-offset needs FROM:TO:STEP");
      if (!ParseOffsetRange(v, &sweep_range, &error))
        return Usage("--sweep-laser-time-offset: " + error);
      sweep = true;
    } else if (a == "--refine") {
      options.refine = MakeRefiner(refine::RefineOptions{});
    } else if (a == "--hypotheses") {
      options.hypotheses = true;
    } else if (a == "--corrected") {
      corrected = true;
    } else if (a == "--seed") {
      const char* v = value();
      if (v == nullptr) return Usage("--seed needs a value");
      if (!SeedArgument(a, v, seed, error)) return Usage(error);
    } else if (a == "--odometry-noise") {
      const char* v = value();
      if (v == nullptr || !SetOdometryNoiseLevel(v, &noise))
        return Usage("--odometry-noise needs default or realistic");
    } else if (a == "--reference") {
      const char* v = value();
      if (v == nullptr || *v == '\0') return Usage("--reference needs a file");
      reference_path = v;
    } else if (a == "--wheel-noise") {
      if (!number(0, 1, noise.wheel_noise_per_m)) return Usage(error);
    } else if (a == "--left-scale") {
      if (!number(-0.5, 0.5, noise.left_scale_error)) return Usage(error);
    } else if (a == "--right-scale") {
      if (!number(-0.5, 0.5, noise.right_scale_error)) return Usage(error);
    } else if (a == "--track-width-error") {
      if (!number(-0.5, 0.5, noise.track_width_error)) return Usage(error);
    } else if (a == "--line-period") {
      if (!number(1e-6, 1, log_options.line_period_s)) return Usage(error);
    } else if (a == "--log-max-range") {
      if (!number(0, 1e6, log_options.max_range_m)) return Usage(error);
    } else if (a == "--skip-bad-lines") {
      log_options.skip_bad_lines = true;
    } else if (a == "--quiet") {
      quiet = true;
    } else if (!a.empty() && a[0] == '-') {
      return Usage("unknown option " + a);
    } else if (log_path.empty()) {
      log_path = a;
    } else {
      return Usage("one LOG only (got " + log_path + " and " + a + ")");
    }
  }
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
  const ReplaySource source = ReadReplaySource(log_path, log_options, RawChannels(channels));
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
  const bool tty = isatty(STDERR_FILENO) != 0;
  const auto start = std::chrono::steady_clock::now();
  auto progress = [&](int64_t done, int64_t total) {
    if (quiet) return;
    const double s =
        std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    std::fprintf(stderr, "%satlas-replay: %lld/%lld scans, %.1f s%s", tty ? "\r" : "",
                 static_cast<long long>(done), static_cast<long long>(total), s, tty ? "" : "\n");
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
  ReplayResult r = corrected || !reference.empty()
                       ? RunReplay(corrected ? synthesized : source.carmen.events, options, out_dir,
                                   progress, 1000, reference)
                       : RunReplay(source.events, options, out_dir, progress, 1000);
  if (!quiet && tty) std::fputc('\n', stderr);
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
