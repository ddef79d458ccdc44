#include "tools/sonar_eval/atlas_mode.h"

#include <algorithm>
#include <array>
#include <cerrno>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <memory>
#include <numbers>
#include <optional>
#include <string>
#include <vector>

#include "core/atlas/atlas.h"
#include "core/atlas/line_map_bootstrapper.h"
#include "core/eval/error_stats.h"
#include "core/localmap/line_ekf_map.h"
#include "core/sonar/sonar_local_map.h"
#include "core/sonar/sonar_map_bootstrapper.h"
#include "sim/simulation.h"
#include "tools/cli/command_line.h"
#include "tools/monte_carlo/nees_band.h"
#include "tools/sonar_eval/corridor_run.h"
#include "tools/sonar_eval/sonar_atlas_run.h"
#include "tools/sonar_eval/world_option.h"

namespace atlas::sonar_eval {
namespace {

using cli::GetIntegerOption;
using cli::GetNumberOption;

// The options' defaults: the maps' capacity and w are atlasd's.
struct AtlasDefaults {
  std::string world = "building";
  int ring = 24;
  int seed = 1;
  int runs = 1;
  double km = 0.4;
  int rooms = 6;
  int capacity = EvalMapCapacity();
  int laser = 1;
  int sonar_w = MapperSettings{}.sonar_bootstrap ? 1 : 0;
  AlcoveLoopOptions loop;
};

// Mean over runs of the per-step NEES (steps where every run has a value), against the 95 %
// band of chi-square(3 runs) / runs, as atlas-localmap-eval mc does for one map.
void PrintNeesBand(const char* name, const std::vector<AtlasRunReport>& runs) {
  const int n = static_cast<int>(runs.size());
  const mc::NeesBand band = mc::MeanNeesBand(3, n);
  std::vector<std::vector<double>> nees;
  for (const AtlasRunReport& r : runs) nees.push_back(r.nees);
  const mc::BandSummary s = mc::SummarizeInBand(mc::MeanPerStep(nees), band);
  std::printf(
      "  robot NEES %s (dominant pose in its frame, mean over %d runs per step): 95%% band "
      "[%.3f, %.3f]; mean %.2f, max %.1f; steps inside %d/%d = %.1f%%, below the upper bound "
      "%.1f%%\n",
      name, n, band.lo, band.hi, s.mean, s.max, s.inside, s.steps, s.InsidePercent(),
      s.BelowPercent());
}

void PrintMatches(const char* name, const std::vector<AtlasRunReport>& runs) {
  int frames = 0, genesis = 0, acc = 0, amb = 0, rej = 0, edges = 0, false_chi2 = 0, gross = 0,
      made_false = 0, made_gross = 0, seeded = 0, matured = 0, deleted = 0, killed = 0,
      over_budget = 0;
  double max_step_ms = 0.0;
  std::array<int, kMapMatchReasonCount> reasons{};
  for (const auto& r : runs) {
    frames += r.frames;
    genesis += r.genesis;
    seeded += r.seeded;
    matured += r.matured;
    deleted += r.deleted;
    killed += r.killed_by_w;
    max_step_ms = std::max(max_step_ms, r.max_step_cpu_ms);
    over_budget += r.steps_over_10ms;
    acc += r.accepted;
    amb += r.ambiguous;
    rej += r.rejected;
    edges += r.closures.map_match_edges;
    false_chi2 += r.closures.false_chi2;
    gross += r.closures.gross;
    for (const replay::ClosureVerdict& v : r.as_made) {
      made_false += v.false_chi2;
      made_gross += v.gross;
    }
    for (int k = 0; k < kMapMatchReasonCount; ++k) reasons[k] += r.reasons[k];
  }
  std::printf(
      "  %s atlas: %d frames (%d Genesis) over %zu runs; map matches accepted %d, refused as "
      "ambiguous %d, rejected %d; by reason:",
      name, frames, genesis, runs.size(), acc, amb, rej);
  for (int k = 0; k < kMapMatchReasonCount; ++k) {
    if (reasons[k] > 0)
      std::printf(" %s %d", MapMatchReasonName(static_cast<MapMatchReason>(k)), reasons[k]);
  }
  std::printf("\n    juveniles: %d seeded, %d matured, %d deleted (%d killed by w)", seeded,
              matured, deleted, killed);
  std::printf("\n    step CPU time: max %.2f ms; %d steps over 10 ms", max_step_ms, over_budget);
  std::printf(
      "\n    map-match edges vs ground truth: %d edges, %d false closures (chi2 3 dof > 14.16), "
      "%d gross (> 0.5 m or 5 deg); as map-matching made them (before edge refinement): %d "
      "false, %d gross\n",
      edges, false_chi2, gross, made_false, made_gross);
  for (size_t i = 0; i < runs.size(); ++i) {
    for (const replay::ClosureVerdict& v : runs[i].closures.edges) {
      const auto made =
          std::find_if(runs[i].as_made.begin(), runs[i].as_made.end(),
                       [&](const replay::ClosureVerdict& m) { return m.a == v.a && m.b == v.b; });
      std::printf(
          "    run %zu edge %d-%d: estimate (%.3f, %.3f, %.2f deg), truth (%.3f, %.3f, %.2f "
          "deg), d2 %.2f (as made %.2f%s): %s\n",
          i + 1, v.a, v.b, v.estimate.x, v.estimate.y, v.estimate.theta * 180.0 / std::numbers::pi,
          v.reference.x, v.reference.y, v.reference.theta * 180.0 / std::numbers::pi, v.d2,
          made == runs[i].as_made.end() ? -1.0 : made->d2,
          v.kind == EdgeKind::kRefined ? ", refined" : "", v.false_chi2 ? "FALSE CLOSURE" : "true");
    }
  }
}

void PrintAtlasErrors(const char* name, const std::vector<AtlasRunReport>& runs, int gap, bool dr) {
  std::vector<double> tr, rot;
  int skipped = 0;
  for (const auto& t : runs) {
    for (size_t i = 0; i + gap < t.truth.size(); i += gap) {
      if (!dr && t.frame[i] != t.frame[i + gap]) {
        ++skipped;
        continue;
      }
      AddPairError(Between(t.truth[i], t.truth[i + gap]),
                   dr ? Between(t.odometry[i], t.odometry[i + gap])
                      : Between(t.estimate[i], t.estimate[i + gap]),
                   tr, rot);
    }
  }
  const eval::ErrorStats et = eval::Summarize(tr), er = eval::Summarize(rot);
  std::printf(
      "    %-22s: trans %.4f +- %.4f m (rmse %.4f, max %.3f), rot %.3f +- %.3f deg, %lld pairs"
      " (%d across frames skipped)\n",
      name, et.mean, et.stddev, et.rmse, et.max, er.mean, er.stddev,
      static_cast<long long>(et.count), skipped);
}

// --trace: one row per step and live hypothesis (the dominant marked), its pose error in its
// frame, what its map made of the reading, and its map's lines against the true walls: the
// largest NEES against the nearest wall and how many lines fit no wall (NEES above
// kLineOffNees).
inline constexpr double kLineOffNees = 13.82;  // chi-square, 2 dof, 99.9 %
struct TraceWriter {
  std::FILE* f = nullptr;
  int run = 0;
  const std::vector<sim::Wall>* walls = nullptr;
  // The walls' lines in each frame (index = frame id), made when the frame is first traced.
  std::vector<std::vector<Vec2>> wall_lines;
  void Row(const Atlas& atlas, Time stamp, const Pose2& truth,
           const std::vector<std::optional<Pose2>>& origin) {
    for (const Hypothesis& h : atlas.Hypotheses()) {
      if (h.frame < 0 || static_cast<size_t>(h.frame) >= origin.size()) continue;
      const UncertainPose p = atlas.PoseOf(h);
      const Pose2 t = Between(*origin[h.frame], truth);
      // The hypothesis's map (a juvenile's trial map) against the true walls.
      const LocalMap& map = h.trial_map ? *h.trial_map : *atlas.Graph().Frame(h.frame).map;
      if (wall_lines.size() <= static_cast<size_t>(h.frame)) wall_lines.resize(h.frame + 1);
      std::vector<Vec2>& in_frame = wall_lines[h.frame];
      if (in_frame.empty()) in_frame = WallLinesInFrame(*walls, *origin[h.frame]);
      double worst = 0.0;
      int off = 0;
      for (const MapLine& l : map.Lines()) {
        const double nees = NeesAgainstNearestWall(l, in_frame);
        worst = std::max(worst, nees);
        off += nees > kLineOffNees ? 1 : 0;
      }
      std::fprintf(
          f,
          "%d\t%.2f\t%lld\t%d\t%s\t%d\t%.3f\t%.2f\t%.3f\t%.3f\t%.4f\t%.3f\t%.3f\t%.4f\t%d\t"
          "%d\t%d\t%d\t%d\t%.1f\t%d\n",
          run, ToSeconds(stamp), static_cast<long long>(h.id), h.frame,
          HypothesisStateName(h.state), h.dominant ? 1 : 0, h.q, PoseNees(p, t), p.mean.x - t.x,
          p.mean.y - t.y, WrapAngle(p.mean.theta - t.theta), std::sqrt(p.cov(0, 0)),
          std::sqrt(p.cov(1, 1)), std::sqrt(p.cov(2, 2)), h.last_update.observations,
          h.last_update.matched, h.last_update.added,
          atlas.Graph().Frame(h.frame).map->Complexity(), h.bootstrapped ? 1 : 0, worst, off);
    }
  }
};

int RunAtlasMode(const cli::ToolOptions& args) {
  const AtlasDefaults d;
  int ring = d.ring, seed = d.seed, rooms = d.rooms, capacity = d.capacity, runs = d.runs,
      laser = d.laser, sonar_w = d.sonar_w, probation = 0;
  double km = d.km;
  AlcoveLoopOptions loop = d.loop;
  std::string error;
  if (!GetIntegerOption(args, "--ring", 16, 24, ring, error) ||
      !GetIntegerOption(args, "--seed", 0, kMaxSeed, seed, error) ||
      !GetNumberOption(args, "--km", 0.01, 100, km, error) ||
      !GetIntegerOption(args, "--rooms", 1, 10000, rooms, error) ||
      !GetIntegerOption(args, "--capacity", 2, 100, capacity, error) ||
      !GetIntegerOption(args, "--runs", 1, 1000, runs, error) ||
      !GetIntegerOption(args, "--laser", 0, 1, laser, error) ||
      !GetIntegerOption(args, "--sonar-w", 0, 1, sonar_w, error) ||
      !GetIntegerOption(args, "--probation", 2, 1000, probation, error) ||
      !GetNumberOption(args, "--period", 0.5, 100, loop.period, error) ||
      !GetNumberOption(args, "--loop-length", 5, 1000, loop.length, error) ||
      !GetNumberOption(args, "--loop-width", 5, 1000, loop.width, error)) {
    std::fprintf(stderr, "atlas-sonar-eval atlas: %s\n", error.c_str());
    return 2;
  }
  if (ring != 16 && ring != 24) {
    std::fprintf(stderr, "atlas-sonar-eval atlas: --ring must be 16 or 24\n");
    return 2;
  }
  const std::string world_name = args.values.count("--world") ? args.values.at("--world") : d.world;
  sim::World world;
  if (std::string e = SelectWorld(world_name, seed, rooms, loop, &world); !e.empty()) {
    std::fprintf(stderr, "atlas-sonar-eval atlas: %s\n", e.c_str());
    return 2;
  }
  std::FILE* trace = nullptr;
  if (args.values.count("--trace")) {
    trace = std::fopen(args.values.at("--trace").c_str(), "w");
    if (!trace) {
      std::fprintf(stderr, "atlas-sonar-eval atlas: cannot write --trace %s: %s\n",
                   args.values.at("--trace").c_str(), std::strerror(errno));
      return 1;
    }
    std::fprintf(trace,
                 "# run\tt\thypothesis\tframe\tstate\tdominant\tq\tnees\tex\tey\tetheta\tsx\tsy\t"
                 "stheta\tobservations\tmatched\tadded\tlines\tbootstrapped\tline_nees_max\t"
                 "lines_off\n");
  }
  const int n = static_cast<int>(runs);
  std::vector<AtlasRunReport> sonar_runs, laser_runs;
  sim::SimulationSummary sum;
  for (int r = 0; r < n; ++r) {
    sim::SimulationOptions so;
    so.length_m = km * 1000.0;
    so.laser = laser != 0;
    so.sonar = true;
    so.sonar_options = SonarOptionsFor(static_cast<int>(ring));
    so.seed = static_cast<uint64_t>(seed) + r;
    if (std::string e = so.Validate(); !e.empty()) {
      std::fprintf(stderr, "atlas-sonar-eval atlas: simulation options: %s\n", e.c_str());
      return 2;
    }
    SimRecording rec;
    sum = sim::Simulate(world, so, rec, [&](double d) {
      std::fprintf(stderr, "\rrun %d/%d: simulated %.0f m   ", r + 1, n, d);
    });
    if (!sum.error.empty() || rec.Empty()) {
      std::fprintf(stderr, "\natlas-sonar-eval atlas: simulation failed: %s\n", sum.error.c_str());
      return 1;
    }
    SonarLocalMapOptions sonar_o = SimulatedMapOptions(
        RangeSensors::kSonar, static_cast<int>(capacity), so.odometry_options, so.sonar_options);
    if (std::string e = sonar_o.Validate(); !e.empty()) {
      std::fprintf(stderr, "\natlas-sonar-eval atlas: sonar map options: %s\n", e.c_str());
      return 2;
    }
    const AtlasOptions ao = SonarEvalAtlasOptions(so.sonar_options.ring, sonar_w != 0, probation);
    if (std::string e = ao.Validate(); !e.empty()) {
      std::fprintf(stderr, "\natlas-sonar-eval atlas: sonar atlas options: %s\n", e.c_str());
      return 2;
    }
    const AtlasOptions laser_ao = LaserEvalAtlasOptions();
    std::shared_ptr<const PoseBootstrapper> sonar_bootstrapper;
    if (sonar_w != 0) sonar_bootstrapper = std::make_shared<SonarMapBootstrapper>();
    Atlas sonar_atlas(
        ao, [sonar_o]() { return std::make_unique<SonarLocalMap>(sonar_o); }, sonar_bootstrapper);
    TraceWriter tw{trace, r + 1, &world.walls, {}};
    sonar_runs.push_back(RunAtlas(
        sonar_atlas, rec, true,
        [&](double f) {
          std::fprintf(stderr, "\rrun %d/%d: sonar atlas %.0f%%   ", r + 1, n, 100 * f);
        },
        trace ? [&](const Atlas& a, Time t, const Pose2& truth,
                    const std::vector<std::optional<Pose2>>& o) { tw.Row(a, t, truth, o); }
              : StepObserver{}));
    if (laser != 0) {
      const LocalMapOptions lm =
          SimulatedMapOptions(RangeSensors::kLaser, static_cast<int>(capacity), so.odometry_options,
                              so.sonar_options)
              .line_map;
      Atlas laser_atlas(
          laser_ao, [lm]() { return std::make_unique<LineEkfMap>(lm); },
          std::make_shared<LineMapBootstrapper>(lm));
      laser_runs.push_back(RunAtlas(laser_atlas, rec, false, [&](double f) {
        std::fprintf(stderr, "\rrun %d/%d: laser atlas %.0f%%   ", r + 1, n, 100 * f);
      }));
    }
  }
  std::fprintf(stderr, "\n");
  if (trace) std::fclose(trace);
  if (world_name == "building") {
    std::printf("building seed %d (%zu walls)", static_cast<int>(seed), world.walls.size());
  } else {
    std::printf("alcove loop %.0f x %.0f m, an alcove every %.1f m (%zu walls)", loop.length,
                loop.width, loop.period, world.walls.size());
  }
  std::printf(
      ", %d run(s) (simulation seeds %d..%d) of %.2f km in %.0f s, %d-transducer ring (specular "
      "misses, multipath), map capacity %d\n",
      n, static_cast<int>(seed), static_cast<int>(seed) + n - 1, sum.distance_m / 1000.0,
      sum.duration_s, static_cast<int>(ring), static_cast<int>(capacity));
  PrintMatches("sonar-only", sonar_runs);
  PrintNeesBand("sonar-only", sonar_runs);
  if (!laser_runs.empty()) {
    PrintMatches("laser-only", laser_runs);
    PrintNeesBand("laser-only", laser_runs);
  }
  for (const int gap_s : {5, 30}) {
    std::printf("  relative-pose errors, pairs %d s apart, same dominant frame at both ends:\n",
                gap_s);
    PrintAtlasErrors("sonar-only atlas", sonar_runs, gap_s * 10, false);
    if (!laser_runs.empty()) PrintAtlasErrors("laser-only atlas", laser_runs, gap_s * 10, false);
    PrintAtlasErrors("dead reckoning", sonar_runs, gap_s * 10, true);
  }
  return 0;
}

}  // namespace

cli::ToolMode AtlasMode() {
  const AtlasDefaults d;
  const auto probation = [](bool w) {
    return std::to_string(SonarEvalAtlasOptions({}, w).lifecycle.probation_scans);
  };
  return {"atlas",
          "sonar-only and laser-only atlases on simulated runs against the truth",
          {{"--world", "building|alcoves", "the world (default " + d.world + ")"},
           RingOption(d.ring),
           {"--seed", "S",
            "the first run's noise seed, and the building's layout (default " +
                std::to_string(d.seed) + ")"},
           {"--runs", "N", "runs, noise seeds S..S+N-1 (default " + std::to_string(d.runs) + ")"},
           {"--km", "K", "distance driven per run, km (default " + cli::HelpNumber(d.km) + ")"},
           {"--rooms", "R", "building: at least R rooms (default " + std::to_string(d.rooms) + ")"},
           {"--capacity", "C",
            "map capacity of both atlases (default " + std::to_string(d.capacity) +
                ", atlasd's atlas.map_capacity)"},
           {"--laser", "0|1", "0: no laser atlas (default " + std::to_string(d.laser) + ")"},
           {"--trace", "FILE",
            "one row per step and live hypothesis of the sonar atlas (default: none)"},
           {"--period", "P",
            "alcoves: an alcove every P metres (default " + cli::HelpNumber(d.loop.period) + ")"},
           {"--loop-length", "L",
            "alcoves: the loop's length, metres (default " + cli::HelpNumber(d.loop.length) + ")"},
           {"--loop-width", "W",
            "alcoves: the loop's width, metres (default " + cli::HelpNumber(d.loop.width) + ")"},
           {"--sonar-w", "0|1",
            "the sonar atlas's w from the sonar, as localmap.sonar_bootstrap (default " +
                std::to_string(d.sonar_w) + ")"},
           {"--probation", "N",
            "the sonar atlas's probation, scans (default atlasd's: " + probation(true) +
                " with w, " + probation(false) + " without)"}},
          RunAtlasMode};
}

}  // namespace atlas::sonar_eval
