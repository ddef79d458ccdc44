#include "tools/sonar_eval/assoc_mode.h"

#include <cmath>
#include <cstdio>
#include <limits>
#include <numbers>
#include <string>
#include <vector>

#include "core/localmap/line_model.h"
#include "core/sonar/sonar_local_map.h"
#include "sim/ray_caster.h"
#include "sim/simulation.h"
#include "tools/cli/command_line.h"
#include "tools/sonar_eval/corridor_run.h"
#include "tools/sonar_eval/sonar_atlas_run.h"
#include "tools/sonar_eval/world_option.h"

namespace atlas::sonar_eval {
namespace {

using cli::GetIntegerOption;
using cli::GetNumberOption;

// The options' defaults.
struct AssocDefaults {
  std::string world = "alcoves";
  int ring = 24;
  int seed = 1;
  double km = 0.15;
  int capacity = 40;
  int show = 10;
};

// The wall whose echo the transducer at `sensor` (world) reports, as the simulator decides it
// (drivers/sim SonarModel::Fire: nearest ray of the cone meeting a wall within the critical
// incidence), or -1 when no ray echoes (specular miss: no return, or a multipath one).
int EchoingWall(const sim::RayCaster& caster, const sim::SonarOptions& so, const Pose2& sensor,
                double beam_width, double max_range) {
  const double critical_cos = std::cos(so.critical_incidence_deg * std::numbers::pi / 180.0);
  double best = std::numeric_limits<double>::infinity();
  int wall = -1;
  const int n = so.rays_per_cone;
  for (int k = 0; k < n; ++k) {
    const double offset = n == 1 ? 0.0 : beam_width * (static_cast<double>(k) / (n - 1) - 0.5);
    const Vec2 u(std::cos(sensor.theta + offset), std::sin(sensor.theta + offset));
    const sim::RayHit hit = caster.Cast(Vec2(sensor.x, sensor.y), u, max_range);
    if (!hit.hit()) continue;
    const sim::Wall& w = caster.wall(hit.wall);
    const Vec2 d = (w.b - w.a).normalized();
    if (std::abs(u.x() * d.y() - u.y() * d.x()) >= critical_cos && hit.range < best) {
      best = hit.range;
      wall = hit.wall;
    }
  }
  return wall;
}

int RunAssocMode(const cli::ToolOptions& args) {
  const AssocDefaults d;
  int ring = d.ring, seed = d.seed, capacity = d.capacity, show = d.show;
  double km = d.km;
  AlcoveLoopOptions loop;
  std::string error;
  if (!GetIntegerOption(args, "--ring", 16, 24, ring, error) ||
      !GetIntegerOption(args, "--seed", 0, kMaxSeed, seed, error) ||
      !GetNumberOption(args, "--km", 0.01, 100, km, error) ||
      !GetIntegerOption(args, "--capacity", 2, 200, capacity, error) ||
      !GetIntegerOption(args, "--show", 0, 1000, show, error)) {
    std::fprintf(stderr, "atlas-sonar-eval assoc: %s\n", error.c_str());
    return 2;
  }
  const std::string world_name = args.values.count("--world") ? args.values.at("--world") : d.world;
  sim::World world;
  if (std::string e = SelectWorld(world_name, seed, 6, loop, &world); !e.empty()) {
    std::fprintf(stderr, "atlas-sonar-eval assoc: %s\n", e.c_str());
    return 2;
  }
  sim::SimulationOptions so;
  so.length_m = km * 1000.0;
  so.laser = false;
  so.sonar = true;
  so.sonar_options = SonarOptionsFor(static_cast<int>(ring));
  so.seed = static_cast<uint64_t>(seed);
  SimRecording rec;
  const sim::SimulationSummary sum = sim::Simulate(world, so, rec);
  if (!sum.error.empty()) {
    std::fprintf(stderr, "atlas-sonar-eval assoc: simulation failed: %s\n", sum.error.c_str());
    return 1;
  }
  const sim::RayCaster caster(world.walls);
  SonarLocalMap map(SimulatedMapOptions(RangeSensors::kSonar, static_cast<int>(capacity),
                                        so.odometry_options, so.sonar_options));
  const auto& ring_mounts = so.sonar_options.ring;
  bool first = true;
  Pose2 last_odo, origin;
  std::vector<Vec2> wall_lines;  // in the map frame, index = the caster's wall index
  int counts[2][3] = {};         // [edge][correct, wrong line, no echo]
  int shown = 0;
  double next_print = 0.0;
  for (const SimRecording::Event& e : rec.Events()) {
    if (!e.sonar) continue;
    const Pose2 truth = rec.TruthAt(e.stamp);
    if (first) {
      origin = truth;
      last_odo = e.odometry;
      wall_lines = WallLinesInFrame(world.walls, origin);
      first = false;
    }
    map.Predict(Between(last_odo, e.odometry));
    last_odo = e.odometry;
    const Pose2 est_before = map.RobotPose().mean;
    const Eigen::VectorXd x_before = map.Ekf().State();
    const SonarUpdate up = map.UpdateSonar(e.reading, ring_mounts, true);
    for (const SonarPairing& p : up.pairings) {
      const SonarReturn& ret = e.reading.returns[p.return_index];
      const SonarTransducer& m = ring_mounts[ret.transducer];
      const int wall =
          EchoingWall(caster, so.sonar_options, Compose(truth, m.pose), m.beam_width, m.max_range);
      // Compared as seen from the robot: the feature from the estimated pose, the wall from the
      // true one (both map and robot may be off together, which is not an association error).
      const Pose2 at = Between(origin, truth);
      const double rho = x_before(3 + 2 * p.feature), alpha = x_before(4 + 2 * p.feature);
      const LinePrediction seen = PredictLine(est_before, rho, alpha);
      Vec2 tw(0, 0);
      int kind = 2;
      if (wall >= 0) {
        tw = wall_lines[wall];
        LinePrediction truth_seen = PredictLine(at, tw.x(), tw.y());
        const Vec2 d = LineInnovation(seen.z, truth_seen);
        kind = std::abs(d.y()) < 0.1 && std::abs(d.x()) < 0.15 ? 0 : 1;
      }
      ++counts[p.edge_echo][kind];
      if (kind != 0 && shown < show) {
        ++shown;
        std::printf(
            "t %.1f: transducer %d range %.2f paired %s with feature %d (seen at rho %.2f alpha "
            "%.1f deg), innovation %.3f; true echo: %s (map frame rho %.2f alpha %.1f deg); "
            "robot error %.3f m\n",
            ToSeconds(e.stamp), ret.transducer, ret.range, p.edge_echo ? "as edge echo" : "in cone",
            p.feature, seen.z.x(), seen.z.y() * 180 / std::numbers::pi, p.innovation,
            wall < 0 ? "none (multipath)" : "another wall", tw.x(), tw.y() * 180 / std::numbers::pi,
            (Vec2(est_before.x, est_before.y) -
             Vec2(Between(origin, truth).x, Between(origin, truth).y))
                .norm());
      }
    }
    if (ToSeconds(e.stamp) >= next_print) {
      next_print += 10.0;
      std::printf("t %.0f s: NEES %.2f, %d lines\n", ToSeconds(e.stamp),
                  PoseNees(map.RobotPose(), Between(origin, truth)), map.Complexity());
    }
  }
  for (int edge = 0; edge < 2; ++edge) {
    std::printf(
        "%s pairings: %d with the true wall's line, %d with another line, %d where no wall "
        "echoes (multipath)\n",
        edge ? "edge-echo" : "in-cone", counts[edge][0], counts[edge][1], counts[edge][2]);
  }
  return 0;
}

}  // namespace

cli::ToolMode AssocMode() {
  const AssocDefaults d;
  return {"assoc",
          "one sonar-only map: each applied return against the wall that echoed it",
          {{"--world", "building|alcoves", "the world (default " + d.world + ")"},
           RingOption(d.ring),
           {"--seed", "S",
            "noise seed, and the building's layout (default " + std::to_string(d.seed) + ")"},
           {"--km", "K", "distance driven, km (default " + cli::HelpNumber(d.km) + ")"},
           {"--capacity", "C", "map capacity (default " + std::to_string(d.capacity) + ")"},
           {"--show", "N",
            "wrong pairings listed, the first N (default " + std::to_string(d.show) + ")"}},
          RunAssocMode};
}

}  // namespace atlas::sonar_eval
