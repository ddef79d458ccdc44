#include "sim/simulation.h"

#include <cmath>
#include <random>

namespace atlas::sim {
namespace {

// Independent seeds for the parts of the run.
uint64_t SubSeed(uint64_t seed, uint64_t part) {
  std::seed_seq seq{static_cast<uint32_t>(seed), static_cast<uint32_t>(seed >> 32),
                    static_cast<uint32_t>(part)};
  uint64_t out[1];
  seq.generate(reinterpret_cast<uint32_t*>(out), reinterpret_cast<uint32_t*>(out) + 2);
  return out[0];
}

}  // namespace

std::string SimulationOptions::Validate() const {
  if (!(length_m > 0.0 && length_m <= 1e7)) return "length must be in (0, 10000] km";
  if (!(odometry_hz >= 1.0 && odometry_hz <= 1000.0)) return "odometry_hz must be in [1, 1000]";
  if (!std::isfinite(start_time) || start_time < 0.0) return "start_time must be >= 0";
  std::string e;
  if (laser && !(e = laser_options.Validate()).empty()) return e;
  if (sonar && !(e = sonar_options.Validate()).empty()) return e;
  if (!(e = odometry_options.Validate()).empty()) return e;
  return motion_options.Validate();
}

int StartNode(const World& world) {
  const Bounds b = WorldBounds(world);
  const Vec2 mid = 0.5 * (b.min + b.max);
  std::vector<int> degree(world.nodes.size(), 0);
  for (const RouteEdge& e : world.edges) ++degree[e.from], ++degree[e.to];
  int start = -1;
  double best = std::numeric_limits<double>::infinity();
  for (size_t i = 0; i < world.nodes.size(); ++i) {
    const double d = (world.nodes[i].position - mid).norm();
    if (degree[i] >= 2 && world.nodes[i].kind == NodeKind::kCorridor && d < best) {
      best = d;
      start = static_cast<int>(i);
    }
  }
  return start;
}

SimulationSummary Simulate(const World& world, const SimulationOptions& o, SimulationSink& sink,
                           const std::function<void(double)>& progress) {
  SimulationSummary summary;
  const int start = StartNode(world);
  // Plan a little longer than asked: the follower's path is a bit shorter than the graph's.
  const std::vector<int> route =
      PlanRoute(world, o.length_m * 1.05 + 10.0, start, SubSeed(o.seed, 1));
  if (route.size() < 2) {
    summary.error =
        "the world has no route graph to drive (needs 'node' and 'edge' lines with a "
        "corridor node of degree >= 2)";
    return summary;
  }
  std::vector<Vec2> waypoints;
  for (int id : route) waypoints.push_back(world.nodes[id].position);
  summary.route_waypoints = static_cast<long>(waypoints.size());

  const RayCaster caster(world.walls);
  DiffDriveFollower robot(o.motion_options, std::move(waypoints));
  WheelOdometryModel odometry(o.odometry_options, SubSeed(o.seed, 2));
  LaserModel laser(o.laser_options, SubSeed(o.seed, 3));
  SonarModel sonar(o.sonar_options, SubSeed(o.seed, 4));

  const double dt = 1.0 / o.odometry_hz;
  const double laser_dt = 1.0 / o.laser_options.rate_hz;
  const double sonar_dt = 1.0 / o.sonar_options.reading_hz;
  long step = 0, laser_n = 0, sonar_n = 0;
  std::vector<Disc> legs;
  double next_progress = 0.0;

  Pose2 truth = robot.pose();
  TruthSample ts{FromSeconds(o.start_time), truth};
  OdometrySample odo = odometry.Step(ts);
  sink.OnTruth(ts);
  sink.OnOdometry(odo, 0.0, 0.0);
  ++summary.truth_samples;

  bool driving = true;
  while (driving && robot.distance() < o.length_m) {
    driving = robot.Step(dt);
    ++step;
    const double t0 = o.start_time + (step - 1) * dt, t1 = o.start_time + step * dt;
    const TruthSample next_truth{FromSeconds(t1), robot.pose()};
    const OdometrySample next_odo = odometry.Step(next_truth);
    // Sensors due in (t0, t1), then the step's own samples at t1, then sensors due at t1.
    auto emit_sensors = [&](bool at_end) {
      while (true) {
        const double tl = o.laser ? o.start_time + (laser_n + 1) * laser_dt : 1e300;
        const double tsn = o.sonar ? o.start_time + (sonar_n + 1) * sonar_dt : 1e300;
        const double t = std::min(tl, tsn);
        if (at_end ? t > t1 + 1e-9 : t >= t1 - 1e-9) break;
        const double f = std::clamp((t - t0) / dt, 0.0, 1.0);
        const Pose2 true_pose = InterpolatePose(truth, next_truth.pose, f);
        const Pose2 odo_pose = InterpolatePose(odo.pose, next_odo.pose, f);
        if (tl <= tsn) {
          legs.clear();
          for (const Person& p : world.people)
            for (const Disc& d : PersonLegs(p, t - o.start_time)) legs.push_back(d);
          sink.OnLaser(laser.Scan(caster, true_pose, FromSeconds(t), legs), odo_pose);
          ++laser_n;
        } else {
          sink.OnSonar(sonar.Read(caster, true_pose, FromSeconds(t)), odo_pose);
          ++sonar_n;
        }
      }
    };
    emit_sensors(false);
    sink.OnTruth(next_truth);
    sink.OnOdometry(next_odo, robot.speed(), robot.turn_rate());
    ++summary.truth_samples;
    emit_sensors(true);
    truth = next_truth.pose;
    odo = next_odo;
    if (progress && robot.distance() >= next_progress) {
      progress(robot.distance());
      next_progress += 100.0;
    }
  }
  summary.distance_m = robot.distance();
  summary.duration_s = step * dt;
  summary.laser_scans = laser_n;
  summary.sonar_readings = sonar_n;
  return summary;
}

}  // namespace atlas::sim
