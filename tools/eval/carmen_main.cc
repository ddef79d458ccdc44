// atlas-carmen: inspects CARMEN logs with the atlasd reader: event counts, dead-reckoned and
// reference trajectories, synthesised odometry for corrected logs. See --help.

#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <optional>
#include <string>
#include <vector>

#include "formats/pose_file.h"
#include "logs/carmen/carmen_log.h"
#include "sim/reference_odometry.h"
#include "tools/cli/carmen_log_options.h"
#include "tools/cli/command_line.h"
#include "tools/cli/odometry_noise_options.h"
#include "tools/eval/carmen_tour.h"
#include "tools/eval/trajectory_files.h"

namespace atlas::eval {
namespace {

constexpr const char* kPoseColumns = "timestamp x y theta";

constexpr const char* kDescription =
    R"(Reads CARMEN logs (plain or gzip) with the atlasd reader (FLASER, ROBOTLASER1, RAWLASER1..4,
ODOM; other messages are counted and ignored). Modes (default --count): one mode only, two
different modes are a usage error; --dump-reference implies --corrected.)";

constexpr const char* kFooter =
    R"(A tour (several logs as one run, scripts/tour.sh): --dump-carmen --append --out FILE, once per
log with that log's reading options; each log goes on 1 s after the last line of FILE, its
odometry moved to start where FILE's ended.

Exit status: 0 done, 1 a log could not be read, is truncated or corrupt, or has no CARMEN
line (message on stderr), 2 bad command line.
)";

constexpr const char* kHostname = "atlas-carmen";

// `text` into `path` (stdout when empty), after what it holds when `append`; false after a
// message on stderr.
bool WriteOutput(const std::string& path, const std::string& text, bool append = false) {
  std::FILE* f = path.empty() ? stdout : std::fopen(path.c_str(), append ? "a" : "w");
  if (f == nullptr) {
    std::perror(("atlas-carmen: " + path).c_str());
    return false;
  }
  bool ok = std::fwrite(text.data(), 1, text.size(), f) == text.size();
  if (!path.empty()) ok = std::fclose(f) == 0 && ok;
  if (!ok)
    std::fprintf(stderr, "atlas-carmen: cannot write %s\n", path.empty() ? "stdout" : path.c_str());
  return ok;
}

// Where the run in the CARMEN log at `path` (`size` bytes) ends: its last ODOM line, read from
// the file's end (the lines --dump-carmen writes are at most a few kB), or an error message.
constexpr std::streamoff kTailBytes = 1 << 16;
std::optional<OdometrySample> LastOdometry(const std::string& path, uintmax_t size,
                                           std::string* error) {
  std::ifstream in(path, std::ios::binary);
  const std::streamoff from =
      std::max<std::streamoff>(0, static_cast<std::streamoff>(size) - kTailBytes);
  std::string tail(static_cast<size_t>(static_cast<std::streamoff>(size) - from), '\0');
  if (!in.seekg(from) || !in.read(tail.data(), static_cast<std::streamsize>(tail.size()))) {
    *error = "cannot read " + path;
    return std::nullopt;
  }
  // A read from inside the file begins inside a line: that line is not used.
  if (from > 0) tail.erase(0, std::min(tail.size(), tail.find('\n') + 1));
  const std::optional<OdometrySample> end = LastOdometryIn(tail);
  if (!end)
    *error = path + ": no ODOM line in its last " + std::to_string(kTailBytes / 1024) +
             " kB to go on from (use --append only with a file --dump-carmen wrote)";
  return end;
}

// --dump-carmen: `events` as CARMEN lines into `output` (stdout when empty), after what
// `output` holds when `append`.
int DumpCarmen(std::vector<carmen::CarmenEvent> events, const std::string& path,
               const std::string& output, bool append) {
  std::string continued;
  std::error_code no_file;
  const uintmax_t size = std::filesystem::file_size(output, no_file);
  if (append && !no_file && size > 0) {
    std::string error;
    const std::optional<OdometrySample> end = LastOdometry(output, size, &error);
    if (!end) {
      std::fprintf(stderr, "atlas-carmen: %s\n", error.c_str());
      return 1;
    }
    events = ContinueRun(std::move(events), *end, std::chrono::seconds(1));
    continued =
        " (going on from " + output + " at " + std::to_string(ToSeconds(end->stamp)) + " s)";
  }
  const CarmenLinesResult lines = CarmenLines(events, kHostname);
  if (!WriteOutput(output, lines.text, append)) return 1;
  std::fprintf(stderr, "atlas-carmen: %s: %lld ODOM and %lld FLASER lines%s\n", path.c_str(),
               static_cast<long long>(lines.odometry_lines),
               static_cast<long long>(lines.laser_lines), continued.c_str());
  if (lines.scans_without_odometry > 0 || lines.scans_not_flaser > 0) {
    std::fprintf(stderr,
                 "atlas-carmen: %s: left out %lld scans without odometry around them and %lld "
                 "whose angles a FLASER line cannot state\n",
                 path.c_str(), static_cast<long long>(lines.scans_without_odometry),
                 static_cast<long long>(lines.scans_not_flaser));
  }
  return 0;
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
  if (const std::string note = carmen::ClampNote(log); !note.empty())
    std::printf("  note: %s\n", note.c_str());
  for (const std::string& r : log.bad_line_reasons) std::printf("  malformed: %s\n", r.c_str());
}

int Main(int argc, char** argv) {
  enum class Mode { kCount, kDumpOdometry, kDumpReference, kDumpCarmen } mode = Mode::kCount;
  carmen::CarmenLogOptions options;
  WheelOdometryNoiseOptions noise;
  uint64_t seed = 1;
  bool corrected = false, json = false;
  std::string output;
  std::vector<std::string> logs;
  cli::CommandLine command_line("atlas-carmen", {"atlas-carmen [options] LOG..."}, kDescription,
                                std::string(kFooter) + kOdometryNoiseHelp);
  CLI::App& app = command_line.app();
  cli::AddPositional(app, "LOG", &logs, "CARMEN logs");
  const std::string modes = "Modes";
  bool count = false, dump_odometry = false, dump_reference = false, dump_carmen = false;
  bool append = false;
  cli::AddFlag(app, "--count", &count,
               "print the lines per message type and the events per type of each LOG")
      .Group(modes);
  cli::AddFlag(app, "--dump-odometry", &dump_odometry,
               "write the dead-reckoned trajectory (odometry pose at each scan) of one\n"
               "LOG as a trajectory file (docs/formats.md) to stdout, or to --out FILE")
      .Group(modes);
  cli::AddFlag(app, "--dump-reference", &dump_reference,
               "write the reference trajectory (pose at each scan) of one corrected LOG")
      .Group(modes);
  cli::AddFlag(app, "--dump-carmen", &dump_carmen,
               "write one LOG as read (with --corrected: its synthesised odometry) as\n"
               "CARMEN ODOM and FLASER lines, to stdout or --out FILE")
      .Group(modes);
  cli::AddFlag(app, "--append", &append,
               "--dump-carmen: append to --out FILE, going on from its last odometry (a tour)")
      .Group(modes);
  const std::string reading = "Reading the log";
  cli::AddCarmenLogOptions(app, reading, &options, &corrected);
  const std::string synthesis =
      "Synthesised odometry (with --corrected, for --dump-odometry and --dump-carmen)";
  cli::AddSeed(app, "--seed", &seed, "random seed (default 1)").Group(synthesis);
  cli::AddOdometryNoiseOptions(app, synthesis, &noise);
  cli::AddText(app, "-o,--out", "FILE", &output, "output file for the dump modes (default stdout)");
  cli::AddFlag(app, "--json", &json, "--count as JSON lines, one object per LOG");
  if (std::optional<int> done = command_line.Parse(argc, argv)) return *done;
  auto Usage = [&](const std::string& what) { return command_line.Usage(what); };
  if (count + dump_odometry + dump_reference + dump_carmen > 1)
    return Usage(
        "--count, --dump-odometry, --dump-reference and --dump-carmen are different modes: give "
        "one");
  if (dump_odometry) mode = Mode::kDumpOdometry;
  if (dump_carmen) mode = Mode::kDumpCarmen;
  if (append && (mode != Mode::kDumpCarmen || output.empty()))
    return Usage("--append needs --dump-carmen and --out FILE");
  if (dump_reference) {
    mode = Mode::kDumpReference;
    corrected = true;
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
    } else if (mode == Mode::kDumpCarmen) {
      return DumpCarmen(
          corrected ? carmen::EventsWithSynthesizedOdometry(r.log, noise, seed) : r.log.events,
          path, output, append);
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
