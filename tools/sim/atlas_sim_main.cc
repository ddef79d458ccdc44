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

#include "sim/building_generator.h"
#include "sim/building_kinds.h"
#include "sim/carmen_writer.h"
#include "sim/simulation.h"
#include "tools/cli/command_line.h"
#include "tools/cli/odometry_noise_options.h"

namespace {

using namespace atlas;
using namespace atlas::sim;

constexpr const char* kDescription =
    R"(Simulates a differential-drive robot driving a route through a building (generated, or read
from a world file) with a SICK-like laser, a sonar ring and noisy wheel odometry, and writes:
  DIR/world.txt   the world (walls and route graph; 'atlas-world 1' format)
  DIR/truth.tsv   ground truth, one row per odometry step: timestamp x y theta
  DIR/run.clf     CARMEN log: ODOM lines, FLASER lines (odometry poses in the odometry
                  fields), SONAR lines (project-specific, see docs/formats.md)
Runs are reproducible from --seed.)";

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
  bool quiet = false, rooms_given = false, kind_given = false, range_given = false,
       no_laser = false;
  BuildingKind kind = BuildingKind::kOffice;
  cli::CommandLine command_line("atlas-sim", {"atlas-sim [options] --out DIR"}, kDescription,
                                kOdometryNoiseHelp);
  CLI::App& app = command_line.app();
  cli::AddText(app, "-o,--out", "DIR", &out_dir,
               "output directory (created; files in it are overwritten)");
  cli::AddValue(
      app, "--kind", "NAME",
      [&](const std::string& v) -> std::string {
        if (!ParseBuildingKind(v, &kind))
          return "--kind must be one of office, curved, clutter, glass, corridor, hall, campus, "
                 "people, got '" +
                 v + "'";
        kind_given = true;
        return "";
      },
      "the kind of building to generate (default office): office, curved,\n"
      "clutter, glass, corridor, hall, campus, people (sim/building_kinds.h);\n"
      "the laser's range defaults to the kind's (campus 80 m)");
  cli::AddInteger(app, "--rooms", "N", 1, 100000, &building.min_rooms,
                  "generate an office with at least N rooms (default 24)")
      .Each([&](const std::string&) { rooms_given = true; });
  cli::AddText(app, "--world", "FILE", &world_file,
               "drive through this world file instead of generating one (not with\n"
               "--rooms or --kind)");
  cli::AddNumber(
      app, "--length-km", "X", 1e-4, 10000, [&](double km) { sim.length_m = 1000 * km; },
      "route length in km (default 0.5)");
  cli::AddSeed(app, "--seed", &sim.seed,
               "random seed for building, route and sensor noise (default 1)");
  cli::AddNumber(app, "--speed", "M_PER_S", 0.05, 5, &sim.motion_options.max_speed,
                 "top speed (default 0.8)");
  cli::AddNumber(app, "--odometry-hz", "HZ", 1, 1000, &sim.odometry_hz,
                 "odometry and ground-truth rate (default 50)");
  cli::AddValue(
      app, "--laser-beams", "181|361",
      [&](const std::string& v) -> std::string {
        if (v != "181" && v != "361")
          return "--laser-beams must be 181 or 361 (1 or 0.5 degree over 180 degrees, as a "
                 "SICK LMS 2xx), got '" +
                 v + "'";
        sim.laser_options.beams = std::stoi(v);
        return "";
      },
      "laser beams over 180 degrees (default 181)");
  cli::AddNumber(app, "--laser-hz", "HZ", 0.1, 1000, &sim.laser_options.rate_hz,
                 "laser scan rate (default 10)");
  cli::AddNumber(app, "--laser-max-range", "M", 0.5, 1000, &sim.laser_options.max_range,
                 "laser maximum range (default 30; the campus 80)")
      .Each([&](const std::string&) { range_given = true; });
  cli::AddNumber(app, "--laser-noise", "M", 0, 1, &sim.laser_options.range_sigma,
                 "laser range noise sigma (default 0.01)");
  cli::AddFlag(app, "--no-laser", &no_laser, "no laser");
  cli::AddChoice(app, "--sonar", "RING", {"none", "p3dx", "b21"}, &sonar_kind,
                 "sonar ring: none, 16 P3-DX or 24 B21-like transducers (default p3dx)");
  cli::AddNumber(app, "--sonar-hz", "HZ", 0.1, 1000, &sim.sonar_options.reading_hz,
                 "sonar readings per second (default 10)");
  cli::AddOdometryNoiseOptions(app, "Odometry", &sim.odometry_options);
  cli::AddFlag(app, "--quiet", &quiet, "no progress output");
  if (std::optional<int> done = command_line.Parse(argc, argv)) return *done;
  if (no_laser) sim.laser = false;
  if (out_dir.empty()) return command_line.Usage("--out DIR is required (where to write the run)");
  if ((rooms_given || kind_given) && !world_file.empty())
    return command_line.Usage(
        "--rooms and --kind generate a building; --world reads one: give one of them");
  if (rooms_given && kind != BuildingKind::kOffice)
    return command_line.Usage("--rooms sizes an office; --kind " + std::string(ToString(kind)) +
                              " has its own size");
  if (!range_given) sim.laser_options.max_range = KindLaserMaxRange(kind);
  if (sonar_kind == "none") {
    sim.sonar = false;
  } else if (sonar_kind == "p3dx") {
    sim.sonar_options.ring = P3dxSonarRing();
  } else {
    sim.sonar_options.ring = B21SonarRing();
  }
  sim.start_time = 1000.0;
  if (std::string e = sim.Validate(); !e.empty()) return command_line.Usage(e);
  if (std::string e = building.Validate(); !e.empty()) return command_line.Usage(e);

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
