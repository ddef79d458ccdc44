// atlas-sim: simulates a robot driving through a generated (or loaded) building and writes the
// run as files every atlasd tool reads (docs/formats.md, "Simulated run").

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <iterator>
#include <string>

#include "core/common/parse_number.h"
#include "core/common/version.h"
#include "sim/building_generator.h"
#include "sim/building_kinds.h"
#include "sim/carmen_writer.h"
#include "sim/simulation.h"

namespace {

using namespace atlas;
using namespace atlas::sim;

constexpr const char* kUsage = R"(usage: atlas-sim [options] --out DIR

Simulates a differential-drive robot driving a route through a building (generated, or read
from a world file) with a SICK-like laser, a sonar ring and noisy wheel odometry, and writes:
  DIR/world.txt   the world (walls and route graph; 'atlas-world 1' format)
  DIR/truth.tsv   ground truth, one row per odometry step: timestamp x y theta
  DIR/run.clf     CARMEN log: ODOM lines, FLASER lines (odometry poses in the odometry
                  fields), SONAR lines (project-specific, see docs/formats.md)
Runs are reproducible from --seed.

options:
  --out DIR               output directory (created; files in it are overwritten)
  --kind NAME             the kind of building to generate (default office): office, curved,
                          clutter, glass, corridor, hall, campus, people (sim/building_kinds.h);
                          the laser's range defaults to the kind's (campus 80 m)
  --rooms N               generate an office with at least N rooms, 1..100000 (default 24)
  --world FILE            drive through this world file instead of generating one (not with
                          --rooms or --kind)
  --length-km X           route length in km (default 0.5)
  --seed N                random seed for building, route and sensor noise, an integer in
                          [0, 18446744073709551615] (default 1)
  --speed M_PER_S         top speed (default 0.8)
  --odometry-hz HZ        odometry and ground-truth rate (default 50)
  --laser-beams 181|361   laser beams over 180 degrees (default 181)
  --laser-hz HZ           laser scan rate (default 10)
  --laser-max-range M     laser maximum range (default 30; the campus 80)
  --laser-noise M         laser range noise sigma (default 0.01)
  --no-laser              no laser
  --sonar none|p3dx|b21   sonar ring: 16 P3-DX or 24 B21-like transducers (default p3dx)
  --sonar-hz HZ           sonar readings per second (default 10)
  --odometry-noise LEVEL  default | realistic (below)
  --track-width M         odometry track width (default 0.4)
  --wheel-noise V         wheel distance variance per metre, m^2/m (default 5e-6)
  --left-scale-error E    left wheel radius error, relative (default 0.0002)
  --right-scale-error E   right wheel radius error, relative (default -0.0002)
  --track-width-error E   track width error, relative (default 0.002)
  --quiet                 no progress output
  --version               the version
  --help                  this text
)";

int Fail(const std::string& message) {
  std::fprintf(stderr, "atlas-sim: %s\n(atlas-sim --help for usage)\n", message.c_str());
  return 2;
}

// Collects output in memory and writes it in large blocks.
class BufferedFile {
 public:
  bool Open(const std::filesystem::path& path) {
    path_ = path;
    file_ = std::fopen(path.c_str(), "wb");
    buffer_.reserve(1 << 21);
    return file_ != nullptr;
  }
  ~BufferedFile() { Close(); }
  std::string* buffer() { return &buffer_; }
  void MaybeFlush() {
    if (buffer_.size() > (1 << 20)) Flush();
  }
  void Flush() {
    if (file_ && !buffer_.empty() &&
        std::fwrite(buffer_.data(), 1, buffer_.size(), file_) != buffer_.size())
      failed_ = true;
    buffer_.clear();
  }
  bool Close() {
    if (!file_) return !failed_;
    Flush();
    if (std::fclose(file_) != 0) failed_ = true;
    file_ = nullptr;
    return !failed_;
  }
  const std::filesystem::path& path() const { return path_; }

 private:
  std::filesystem::path path_;
  std::FILE* file_ = nullptr;
  std::string buffer_;
  bool failed_ = false;
};

class FileSink : public SimulationSink {
 public:
  FileSink(BufferedFile* truth, BufferedFile* log) : truth_(truth), log_(log) {}
  void OnTruth(const TruthSample& t) override {
    AppendTruthRow(truth_->buffer(), t);
    truth_->MaybeFlush();
  }
  void OnOdometry(const OdometrySample& o, double tv, double rv) override {
    AppendOdomLine(log_->buffer(), o, tv, rv);
    log_->MaybeFlush();
  }
  void OnLaser(const LaserScan& scan, const Pose2& odometry) override {
    AppendFlaserLine(log_->buffer(), scan, odometry);
    log_->MaybeFlush();
  }
  void OnSonar(const SonarReading& reading, const Pose2& odometry) override {
    AppendSonarLine(log_->buffer(), reading, odometry);
    log_->MaybeFlush();
  }

 private:
  BufferedFile* truth_;
  BufferedFile* log_;
};

}  // namespace

int main(int argc, char** argv) {
  const auto wall_start = std::chrono::steady_clock::now();
  SimulationOptions sim;
  sim.length_m = 500.0;
  sim.sonar = true;
  BuildingOptions building;
  std::string out_dir, world_file, sonar_kind = "p3dx";
  bool quiet = false, rooms_given = false, kind_given = false, range_given = false;
  BuildingKind kind = BuildingKind::kOffice;
  for (int i = 1; i < argc; ++i) {
    const std::string a = argv[i];
    if (a == "--version") {
      std::fputs(atlas::VersionLine("atlas-sim").c_str(), stdout);
      return 0;
    }
    if (a == "--help" || a == "-h") {
      std::fputs(kUsage, stdout);
      std::fputs(kOdometryNoiseHelp, stdout);
      return 0;
    }
    if (a == "--no-laser") {
      sim.laser = false;
      continue;
    }
    if (a == "--quiet") {
      quiet = true;
      continue;
    }
    static const char* const kWithValue[] = {"--out",
                                             "--world",
                                             "--rooms",
                                             "--kind",
                                             "--odometry-noise",
                                             "--length-km",
                                             "--seed",
                                             "--speed",
                                             "--odometry-hz",
                                             "--laser-beams",
                                             "--laser-hz",
                                             "--laser-max-range",
                                             "--laser-noise",
                                             "--sonar",
                                             "--sonar-hz",
                                             "--track-width",
                                             "--wheel-noise",
                                             "--left-scale-error",
                                             "--right-scale-error",
                                             "--track-width-error"};
    if (std::find(std::begin(kWithValue), std::end(kWithValue), a) == std::end(kWithValue))
      return Fail("unknown option '" + a + "'");
    if (i + 1 >= argc) return Fail("option " + a + " needs a value");
    const char* v = argv[++i];
    std::string error;
    auto number = [&](double lo, double hi) {
      double x = 0.0;
      if (!NumberArgument(a, v, lo, hi, x, error)) std::exit(Fail(error));
      return x;
    };
    auto integer = [&](int64_t lo, int64_t hi, auto* out) {
      if (!IntegerArgument(a, v, lo, hi, *out, error)) std::exit(Fail(error));
    };
    if (a == "--out") {
      out_dir = v;
    } else if (a == "--world") {
      world_file = v;
    } else if (a == "--kind") {
      if (!ParseBuildingKind(v, &kind))
        return Fail(
            "--kind must be one of office, curved, clutter, glass, corridor, hall, "
            "campus, people, not '" +
            std::string(v) + "'");
      kind_given = true;
    } else if (a == "--odometry-noise") {
      if (!SetOdometryNoiseLevel(v, &sim.odometry_options))
        return Fail("--odometry-noise must be default or realistic, not '" + std::string(v) + "'");
    } else if (a == "--rooms") {
      integer(1, 100000, &building.min_rooms);
      rooms_given = true;
    } else if (a == "--length-km") {
      sim.length_m = 1000.0 * number(1e-4, 10000);
    } else if (a == "--seed") {
      if (!SeedArgument(a, v, sim.seed, error)) return Fail(error);
    } else if (a == "--speed") {
      sim.motion_options.max_speed = number(0.05, 5);
    } else if (a == "--odometry-hz") {
      sim.odometry_hz = number(1, 1000);
    } else if (a == "--laser-beams") {
      integer(1, 100000, &sim.laser_options.beams);
      if (sim.laser_options.beams != 181 && sim.laser_options.beams != 361)
        return Fail(
            "--laser-beams must be 181 or 361 (1 or 0.5 degree over 180 degrees, as a "
            "SICK LMS 2xx), not " +
            std::string(v));
    } else if (a == "--laser-hz") {
      sim.laser_options.rate_hz = number(0.1, 1000);
    } else if (a == "--laser-max-range") {
      sim.laser_options.max_range = number(0.5, 1000);
      range_given = true;
    } else if (a == "--laser-noise") {
      sim.laser_options.range_sigma = number(0, 1);
    } else if (a == "--sonar") {
      sonar_kind = v;
    } else if (a == "--sonar-hz") {
      sim.sonar_options.reading_hz = number(0.1, 1000);
    } else if (a == "--track-width") {
      sim.odometry_options.track_width_m = number(0.05, 10);
    } else if (a == "--wheel-noise") {
      sim.odometry_options.wheel_noise_per_m = number(0, 1);
    } else if (a == "--left-scale-error") {
      sim.odometry_options.left_scale_error = number(-0.5, 0.5);
    } else if (a == "--right-scale-error") {
      sim.odometry_options.right_scale_error = number(-0.5, 0.5);
    } else if (a == "--track-width-error") {
      sim.odometry_options.track_width_error = number(-0.5, 0.5);
    }
  }
  if (out_dir.empty()) return Fail("--out DIR is required (where to write the run)");
  if ((rooms_given || kind_given) && !world_file.empty())
    return Fail("--rooms and --kind generate a building; --world reads one: give one of them");
  if (rooms_given && kind != BuildingKind::kOffice)
    return Fail("--rooms sizes an office; --kind " + std::string(ToString(kind)) +
                " has its own size");
  if (!range_given) sim.laser_options.max_range = KindLaserMaxRange(kind);
  if (sonar_kind == "none") {
    sim.sonar = false;
  } else if (sonar_kind == "p3dx") {
    sim.sonar_options.ring = P3dxSonarRing();
  } else if (sonar_kind == "b21") {
    sim.sonar_options.ring = B21SonarRing();
  } else {
    return Fail("--sonar must be none, p3dx or b21, not '" + sonar_kind + "'");
  }
  sim.start_time = 1000.0;
  if (std::string e = sim.Validate(); !e.empty()) return Fail(e);
  if (std::string e = building.Validate(); !e.empty()) return Fail(e);

  World world;
  if (world_file.empty()) {
    world = kind == BuildingKind::kOffice ? GenerateBuilding(building, sim.seed)
                                          : GenerateKind(kind, sim.seed);
  } else {
    std::ifstream in(world_file);
    if (!in) return Fail("cannot open world file '" + world_file + "'");
    WorldParseResult parsed = ParseWorld(in, world_file);
    if (!parsed.ok()) return Fail(parsed.error);
    world = std::move(parsed.world);
  }

  if (StartNode(world) < 0)
    return Fail((world_file.empty() ? std::string("generated world") : world_file) +
                ": no route graph to drive (needs 'node' and 'edge' lines with a corridor node "
                "of degree >= 2; see docs/formats.md)");
  std::error_code ec;
  std::filesystem::create_directories(out_dir, ec);
  if (ec) return Fail("cannot create output directory '" + out_dir + "': " + ec.message());
  const std::filesystem::path dir(out_dir);
  {
    std::ofstream w(dir / "world.txt");
    WriteWorld(w, world);
    if (!w) return Fail("cannot write " + (dir / "world.txt").string());
  }
  BufferedFile truth_file, log_file;
  if (!truth_file.Open(dir / "truth.tsv") || !log_file.Open(dir / "run.clf"))
    return Fail("cannot open output files in '" + out_dir + "' for writing");
  truth_file.buffer()->append("# timestamp\tx\ty\ttheta   (ground truth, s m m rad)\n");
  std::string* h = log_file.buffer();
  *h += "# atlas-sim run: CARMEN log (ODOM, FLASER) plus SONAR lines; see docs/formats.md\n";
  *h += "# seed " + std::to_string(sim.seed) + ", laser " +
        (sim.laser ? std::to_string(sim.laser_options.beams) + " beams at " +
                         std::to_string(sim.laser_options.rate_hz) + " Hz"
                   : std::string("off")) +
        ", sonar " + (sim.sonar ? sonar_kind : std::string("off")) + "\n";
  if (sim.sonar) {
    *h += "# SONAR_GEOMETRY index x y theta beam_width max_range\n";
    for (size_t i = 0; i < sim.sonar_options.ring.size(); ++i) {
      const SonarTransducer& t = sim.sonar_options.ring[i];
      char line[160];
      std::snprintf(line, sizeof(line), "# SONAR_GEOMETRY %zu %.4f %.4f %.5f %.5f %.2f\n", i,
                    t.pose.x, t.pose.y, t.pose.theta, t.beam_width, t.max_range);
      *h += line;
    }
  }

  if (!quiet)
    std::fprintf(stderr,
                 "atlas-sim: world: %zu walls, %d rooms, %zu route nodes; driving %.2f km\n",
                 world.walls.size(), world.CountNodes(NodeKind::kRoom), world.nodes.size(),
                 sim.length_m / 1000.0);
  FileSink sink(&truth_file, &log_file);
  double next_report = 0.1 * sim.length_m;
  const SimulationSummary s = Simulate(world, sim, sink, [&](double d) {
    if (quiet || d < next_report) return;
    next_report += 0.1 * sim.length_m;
    const double secs =
        std::chrono::duration<double>(std::chrono::steady_clock::now() - wall_start).count();
    std::fprintf(stderr, "atlas-sim: %6.2f / %.2f km  (%.1f s)\n", d / 1000.0,
                 sim.length_m / 1000.0, secs);
  });
  if (!s.error.empty()) return Fail(world_file.empty() ? s.error : world_file + ": " + s.error);
  const bool ok = truth_file.Close() & log_file.Close();
  if (!ok) return Fail("writing the output in '" + out_dir + "' failed (disk full?)");
  const double wall =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - wall_start).count();
  std::fprintf(stderr,
               "atlas-sim: done: %.3f km driven in %.1f s simulated (%.2f h), %ld truth samples, "
               "%ld laser scans, %ld sonar readings, %d rooms; wall time %.2f s; output in %s\n",
               s.distance_m / 1000.0, s.duration_s, s.duration_s / 3600.0, s.truth_samples,
               s.laser_scans, s.sonar_readings, world.CountNodes(NodeKind::kRoom), wall,
               out_dir.c_str());
  return 0;
}
