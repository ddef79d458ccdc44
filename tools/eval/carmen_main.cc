// atlas-carmen: inspects CARMEN logs with the atlasd reader: event counts, dead-reckoned and
// reference trajectories, synthesised odometry for corrected logs. See --help.

#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <iterator>
#include <string>
#include <vector>

#include "core/common/parse_number.h"
#include "core/common/version.h"
#include "formats/pose_file.h"
#include "logs/carmen/carmen_log.h"
#include "sim/reference_odometry.h"
#include "tools/eval/trajectory_files.h"

namespace atlas::eval {
namespace {

constexpr const char* kPoseColumns = "timestamp x y theta";

constexpr const char* kHelp = R"(Usage: atlas-carmen [options] LOG...

Reads CARMEN logs (plain or gzip) with the atlasd reader (FLASER, ROBOTLASER1, RAWLASER1..4,
ODOM; other messages are counted and ignored).

Modes (default --count):
  --count              print the lines per message type and the events per type of each LOG
  --dump-odometry      write the dead-reckoned trajectory (odometry pose at each scan) of one
                       LOG as a trajectory file (docs/formats.md) to stdout, or to -o FILE
  --dump-reference     write the reference trajectory (pose at each scan) of one corrected LOG
                       (one mode only: two different modes are a usage error)

Reading:
  --corrected          a "corrected" log: the line order is the clock and the poses are the
                       reference trajectory, not odometry (implied by --dump-reference)
  --line-period S      seconds per line for the line-order clock (default 0.05)
  --max-range M        ranges >= M metres are no-return (default: the line's own maximum, or
                       80 m for FLASER; aces-corrected clamps at 50)
  --skip-bad-lines     count malformed lines instead of stopping at the first

Synthesised odometry (with --corrected and --dump-odometry):
  --seed N             random seed, an integer in [0, 18446744073709551615] (default 1)
  --odometry-noise LEVEL  default | realistic (below)
  --track-width M      nominal track width (default 0.4)
  --wheel-noise V      wheel distance variance per metre rolled, m^2/m (default 5e-6)
  --left-scale E       left wheel scale error (default 0.0002)
  --right-scale E      right wheel scale error (default -0.0002)
  --track-width-error E  relative track width error (default 0.002)

Other:
  -o FILE              output file for the dump modes (default stdout)
  --json               --count as JSON lines, one object per LOG
  --version            the version
  -h, --help           this text

Exit status: 0 done, 1 a log could not be read, is truncated or corrupt, or has no CARMEN
line (message on stderr), 2 bad command line.
)";

int Usage(const std::string& what) {
  std::fprintf(stderr, "atlas-carmen: %s\nTry 'atlas-carmen --help'.\n", what.c_str());
  return 2;
}

void PrintCounts(const std::string& path, const carmen::CarmenLog& log, bool json) {
  if (json) {
    std::string types;
    for (const auto& [name, n] : log.lines_by_message) {
      types += (types.empty() ? "" : ", ") + JsonString(name) + ": " + std::to_string(n);
    }
    std::printf(
        "{\"log\": %s, \"lines\": %lld, \"lines_by_message\": {%s}, \"comment_or_blank\": %lld, "
        "\"bad_lines\": %lld, \"laser_events\": %lld, \"odometry_events\": %lld, "
        "\"reference_poses\": %zu, \"out_of_order_lines\": %lld, \"beams\": %lld, "
        "\"no_return_beams\": %lld, \"largest_range\": %.3f, \"largest_range_count\": %lld}\n",
        JsonString(path).c_str(), static_cast<long long>(log.lines), types.c_str(),
        static_cast<long long>(log.comment_or_blank_lines), static_cast<long long>(log.bad_lines),
        static_cast<long long>(log.laser_events), static_cast<long long>(log.odometry_events),
        log.reference.size(), static_cast<long long>(log.out_of_order_lines),
        static_cast<long long>(log.beams), static_cast<long long>(log.no_return_beams),
        log.largest_range, static_cast<long long>(log.largest_range_count));
    return;
  }
  std::printf("%s\n  lines %lld:", path.c_str(), static_cast<long long>(log.lines));
  for (const auto& [name, n] : log.lines_by_message) {
    std::printf(" %s %lld,", name.c_str(), static_cast<long long>(n));
  }
  std::printf(" comment/blank %lld, malformed %lld\n",
              static_cast<long long>(log.comment_or_blank_lines),
              static_cast<long long>(log.bad_lines));
  std::printf("  events: laser %lld, odometry %lld; reference poses %zu; out-of-order lines %lld\n",
              static_cast<long long>(log.laser_events), static_cast<long long>(log.odometry_events),
              log.reference.size(), static_cast<long long>(log.out_of_order_lines));
  if (!log.events.empty()) {
    std::printf("  stamps %.6f .. %.6f s\n", ToSeconds(StampOf(log.events.front().event)),
                ToSeconds(StampOf(log.events.back().event)));
  }
  std::printf("  beams %lld, no-return %lld; largest range %.2f m (%lld beams)\n",
              static_cast<long long>(log.beams), static_cast<long long>(log.no_return_beams),
              log.largest_range, static_cast<long long>(log.largest_range_count));
  for (const std::string& r : log.bad_line_reasons) std::printf("  malformed: %s\n", r.c_str());
}

bool WriteOutput(const std::string& path, const std::string& text) {
  std::FILE* f = path.empty() ? stdout : std::fopen(path.c_str(), "w");
  if (f == nullptr) {
    std::perror(("atlas-carmen: " + path).c_str());
    return false;
  }
  const bool ok = std::fwrite(text.data(), 1, text.size(), f) == text.size();
  if (!path.empty() && std::fclose(f) != 0) return false;
  return ok;
}

int Main(int argc, char** argv) {
  enum class Mode { kCount, kDumpOdometry, kDumpReference } mode = Mode::kCount;
  std::string mode_option;  // the mode given, to refuse a second, different one
  carmen::CarmenLogOptions options;
  WheelOdometryNoiseOptions noise;
  uint64_t seed = 1;
  bool corrected = false, json = false;
  std::string output;
  std::vector<std::string> logs;
  struct NumberOption {
    const char* name;
    double lo, hi;
    double* out;
  };
  const NumberOption numbers[] = {
      {"--line-period", 1e-6, 1, &options.line_period_s},
      {"--max-range", 0, 1e6, &options.max_range_m},
      {"--track-width", 0.05, 10, &noise.track_width_m},
      {"--wheel-noise", 0, 1, &noise.wheel_noise_per_m},
      {"--left-scale", -0.5, 0.5, &noise.left_scale_error},
      {"--right-scale", -0.5, 0.5, &noise.right_scale_error},
      {"--track-width-error", -0.5, 0.5, &noise.track_width_error},
  };
  for (int i = 1; i < argc; ++i) {
    const std::string a = argv[i];
    if (a == "--version") {
      std::fputs(atlas::VersionLine("atlas-carmen").c_str(), stdout);
      return 0;
    }
    if (a == "-h" || a == "--help") {
      std::fputs(kHelp, stdout);
      std::fputs(kOdometryNoiseHelp, stdout);
      return 0;
    } else if (a == "--count" || a == "--dump-odometry" || a == "--dump-reference") {
      if (!mode_option.empty() && mode_option != a)
        return Usage(mode_option + " and " + a + " are different modes: give one");
      mode_option = a;
      mode = a == "--count"           ? Mode::kCount
             : a == "--dump-odometry" ? Mode::kDumpOdometry
                                      : Mode::kDumpReference;
      if (mode == Mode::kDumpReference) corrected = true;
    } else if (a == "--corrected") {
      corrected = true;
    } else if (a == "--skip-bad-lines") {
      options.skip_bad_lines = true;
    } else if (a == "--json") {
      json = true;
    } else if (a == "-o") {
      if (i + 1 >= argc) return Usage("-o needs a file name");
      output = argv[++i];
    } else if (a == "--odometry-noise") {
      if (i + 1 >= argc || !SetOdometryNoiseLevel(argv[++i], &noise))
        return Usage("--odometry-noise needs default or realistic");
    } else if (a == "--seed") {
      std::string error;
      if (i + 1 >= argc) return Usage("--seed needs an integer");
      if (!SeedArgument(a, argv[++i], seed, error)) return Usage(error);
    } else if (const NumberOption* n =
                   std::find_if(std::begin(numbers), std::end(numbers),
                                [&](const NumberOption& o) { return a == o.name; });
               n != std::end(numbers)) {
      std::string error;
      if (i + 1 >= argc) return Usage(a + " needs a value");
      if (!NumberArgument(a, argv[++i], n->lo, n->hi, *n->out, error)) return Usage(error);
    } else if (!a.empty() && a[0] == '-') {
      return Usage("unknown option " + a);
    } else {
      logs.push_back(a);
    }
  }
  if (logs.empty()) return Usage("no LOG given");
  if (mode != Mode::kCount && logs.size() != 1) return Usage("the dump modes take one LOG");
  if (corrected) {
    options.clock = carmen::Clock::kLineOrder;
    options.reference_trajectory = true;
  }
  if (std::string bad = options.Validate(); !bad.empty()) return Usage(bad);
  if (std::string bad = noise.Validate(); !bad.empty()) return Usage(bad);

  int status = 0;
  for (const std::string& path : logs) {
    if (logs.size() > 1 || mode != Mode::kCount) {
      std::fprintf(stderr, "atlas-carmen: reading %s ...\n", path.c_str());
    }
    carmen::CarmenReadResult r = carmen::ReadCarmenLog(path, options);
    if (!r.ok()) {
      std::fprintf(stderr, "atlas-carmen: %s\n", r.error.c_str());
      if (r.status == carmen::ReadStatus::kBadLine) {
        std::fprintf(stderr, "atlas-carmen: use --skip-bad-lines to count such lines and go on\n");
      }
      status = 1;
      continue;
    }
    if (r.log.lines == r.log.comment_or_blank_lines) {
      std::fprintf(stderr, "atlas-carmen: %s: no lines%s: is this a CARMEN log?\n", path.c_str(),
                   r.log.lines == 0 ? "" : " but comments and blank lines");
      status = 1;
      continue;
    }
    if (mode == Mode::kCount) {
      PrintCounts(path, r.log, json);
    } else if (mode == Mode::kDumpReference) {
      const TimedTrajectory t = ReferenceAtScans(r.log);
      if (t.empty()) {
        std::fprintf(stderr, "atlas-carmen: %s has no laser line with a pose\n", path.c_str());
        return 1;
      }
      if (!WriteOutput(output, formats::FormatPoseRows(
                                   t.poses(), "reference trajectory of " + path +
                                                  " (line-order clock)\n" + kPoseColumns))) {
        return 1;
      }
    } else {
      std::string comment = "dead reckoning of " + path;
      TimedTrajectory t;
      if (corrected) {
        t = OdometryAtScans(carmen::EventsWithSynthesizedOdometry(r.log, noise, seed));
        comment += " (odometry synthesised from the reference, seed " + std::to_string(seed) +
                   ", line-order clock)";
      } else {
        t = OdometryAtScans(r.log.events);
      }
      if (t.empty()) {
        std::fprintf(stderr, "atlas-carmen: %s: no scan has odometry around it\n", path.c_str());
        return 1;
      }
      if (!WriteOutput(output, formats::FormatPoseRows(t.poses(), comment + "\n" + kPoseColumns)))
        return 1;
    }
  }
  return status;
}

}  // namespace
}  // namespace atlas::eval

int main(int argc, char** argv) { return atlas::eval::Main(argc, argv); }
