// atlas-sonar-eval: evaluation of sonar-only line mapping (issue 7).
//
//   atlas-sonar-eval mc   [--runs N] [--minutes M] [--ring 16|24] [--seed S] [--capacity C]
//       Seeded simulator runs in a corridor (sim ray caster; sonar ring with specular
//       misses and multipath; laser; wheel odometry). On each run a sonar-only and a laser-only
//       SonarLocalMap process the same odometry: robot NEES against the 95 % band, and
//       relative-pose errors (pairs 5, 30, 90 s apart) against ground truth for sonar, laser and
//       dead reckoning.
//   atlas-sonar-eval fig9 [--png F] [--ring 16|24] [--seed S] [--lines K]
//       A picture like the paper's Fig. 9: the returns (arcs), vantage points and the lines
//       the first K initialisations made, over the true walls.

#include <Eigen/Cholesky>
#include <algorithm>
#include <cerrno>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <limits>
#include <map>
#include <numbers>
#include <optional>
#include <string>
#include <vector>

#include "core/atlas/atlas.h"
#include "core/atlas/line_map_bootstrapper.h"
#include "core/eval/error_stats.h"
#include "core/localmap/jcbb.h"
#include "core/localmap/line_model.h"
#include "core/sonar/sonar_local_map.h"
#include "core/sonar/sonar_map_bootstrapper.h"
#include "sim/building_generator.h"
#include "sim/corridor.h"
#include "sim/laser_model.h"
#include "sim/ray_caster.h"
#include "sim/route.h"
#include "sim/simulation.h"
#include "sim/sonar_model.h"
#include "sim/wheel_odometry_model.h"
#include "tools/eval/tool_options.h"
#include "tools/eval/trajectory_files.h"
#include "tools/render/canvas.h"
#include "tools/sonar_eval/alcove_loop_world.h"
#include "tools/sonar_eval/sonar_atlas_run.h"

namespace atlas {
namespace {

constexpr char kUsage[] =
    "usage: atlas-sonar-eval mc   [--runs N=20] [--minutes M=3] [--ring 16|24 (24)] [--seed S=1]\n"
    "                             [--capacity C=20] [--delayed-states 0|1 (1)]\n"
    "                             [--point-rival 0|1 (1)] [--init-edge-echoes 0|1 (0)]\n"
    "                             [--extent-gap G=1.5] [--model-sigma M=0.02]\n"
    "       atlas-sonar-eval fig9 [--png F=sonar_fig9.png] [--ring 16|24 (24)] [--seed S=1]\n"
    "                             [--lines K=4] [--phantoms 0|1 (0)] [--minutes M=3]\n"
    "       atlas-sonar-eval atlas [--world building|alcoves (building)] [--ring 16|24 (24)]\n"
    "                             [--seed S=1] [--runs N=1] [--km K=0.4] [--capacity C=10]\n"
    "                             [--laser 0|1 (1)] [--self-match 0|1 (1)] [--trace FILE]\n"
    "                             [--delayed-states 0|1 (1)] [--edge-extent 0|1 (1)]\n"
    "                             [--point-rival 0|1 (1)] [--init-edge-echoes 0|1 (0)]\n"
    "                             [--redundancy-sigma S=0.25] [--redundancy-prior H=0.5]\n"
    "                             [--alternative-sigmas A=3]\n"
    "                             [--line-correlation 0|1 (1)] [--keep-frame-map 0|1 (0)]\n"
    "                             [--seed-cov-scale F=1] [--sonar-w 0|1 (1)]\n"
    "                             [--bootstrap-steps N] [--probation N] [--w-edge-echoes 0|1 (0)]\n"
    "                             [--w-dead-reckoned 0|1 (1)]\n"
    "                             [--extent-gap G=1.5] [--model-sigma M=0.02]\n"
    "                             building: [--rooms R=6]; alcoves: [--period P=4]\n"
    "                             [--loop-length L=36] [--loop-width W=14]\n"
    "       atlas-sonar-eval assoc [--world alcoves|building (alcoves)] [--ring 16|24 (24)]\n"
    "                             [--seed S=1] [--km K=0.15] [--capacity C=40] [--show N=10]\n"
    "\n"
    "mc:   simulated 20 m corridor, robot driving back and forth; on each seeded run a sonar-only\n"
    "      and a laser-only local map (same odometry). Prints the robot NEES (3 dof) against its\n"
    "      95 % band, the NEES of each sonar line at its initialisation against the nearest true\n"
    "      wall (2 dof, and 5 dof with the robot pose), and relative-pose errors over pairs 5, 30\n"
    "      and 90 s apart for sonar, laser and dead reckoning.\n"
    "      --delayed-states 0 (mc, atlas): new sonar lines with the earlier approximation\n"
    "      (vantage points independent of the map, SonarInitOptions::delayed_states) for\n"
    "      comparison.\n"
    "      --point-rival 0 (mc, atlas): new sonar lines without the point-reflector rival test\n"
    "      (SonarInitOptions::point_rival); --init-edge-echoes 1: RANSAC with edge-of-cone\n"
    "      echoes (SonarInitOptions::edge_echoes). Both for comparison.\n"
    "      --extent-gap G (mc, atlas): how far beyond a line's seen extent a return may still\n"
    "      update it (SonarUpdateOptions::max_extent_gap, metres).\n"
    "      --model-sigma M (mc, atlas): the sonar model's misfit noise per return\n"
    "      (SonarModelOptions::model_sigma, metres; default atlasd's).\n"
    "      --edge-extent 0 (atlas): edge echoes grow extents to where the edge ray meets the line\n"
    "      (SonarUpdateOptions::edge_extent_footprint off) for comparison.\n"
    "atlas: N simulated runs (noise seeds S..S+N-1) with laser and sonar through a world: the\n"
    "      building with corridor loops of atlas-sim (R rooms, layout from --seed), or 'alcoves':\n"
    "      one L x W corridor loop with an alcove every P metres (repetitive structure: Condition\n"
    "      2). On each run a sonar-only atlas (SonarLocalMap) and a laser-only atlas (LineEkfMap;\n"
    "      --laser 0: none). Prints frames, map-matching outcomes by reason (accepted / refused\n"
    "      as ambiguous / rejected), every map-match edge against the ground truth (chi-square\n"
    "      3 dof > 14.16: false closure), the robot NEES of the dominant pose in its frame\n"
    "      averaged over the runs against its 95 % band, and relative-pose errors (5 s, 30 s)\n"
    "      next to dead reckoning. --trace FILE: one row per step and live hypothesis (its\n"
    "      pose error, and its map's lines against the true walls).\n"
    "      --self-match 0: map-matching without the self-match test of repetitive structure\n"
    "      (what Condition 2's refusals protect against). --redundancy-sigma S: the sonar atlas's\n"
    "      map_match redundancy_sigma (0: a direction of t may rest on one line pair),\n"
    "      --redundancy-prior H its redundancy_prior_halfwidth (0: never; SonarAtlasOptions);\n"
    "      --alternative-sigmas A its alternative_sigmas (0: off; SonarAtlasOptions).\n"
    "      --line-correlation 0: map_match's unknown_line_correlation off (t's covariance not\n"
    "      times the pairs; on in SonarAtlasOptions since session 16). Each edge is also judged\n"
    "      as map-matching made it (before edge refinement).\n"
    "      --keep-frame-map 1 (with --sonar-w 0): a juvenile that matures leaves the frame's map\n"
    "      as it was (not the features it updated from its seeded pose) and gives it its robot\n"
    "      pose (AtlasOptions::keep_frame_map_without_w, an experiment).\n"
    "      --seed-cov-scale F (with --sonar-w 0): traversal seeds of the sonar atlas get F times\n"
    "      the projected covariance (AtlasOptions::seed_cov_scale_without_w, an experiment).\n"
    "      --sonar-w 1 (default, as atlasd): the sonar atlas with w (eq. 12;\n"
    "      SonarMapBootstrapper); 0: its juveniles keep their seeded pose and trial map.\n"
    "      --bootstrap-steps N,\n"
    "      --probation N: the sonar atlas's lifecycle.bootstrap_scans and probation_scans\n"
    "      (default: SonarAtlasOptions', with w at least kSonarBootstrapProbation).\n"
    "      --w-edge-echoes 1: w pairs edge-of-cone echoes too (SonarBootstrapOptions::\n"
    "      edge_echoes).\n"
    "      --w-dead-reckoned 1 (default, as atlasd): w starts from the juvenile's seed moved by\n"
    "      the odometry of its readings; 0: from the juvenile's current pose\n"
    "      (SonarBootstrapOptions::dead_reckoned_start).\n"
    "assoc: one sonar-only local map (no atlas) through the world: every return the map applied\n"
    "      to a feature is checked against the wall the simulator echoed it from (in-cone and\n"
    "      edge-of-cone pairings: the true wall's line, another line, or no wall: multipath);\n"
    "      the first N wrong pairings are listed; NEES every 10 s.\n"
    "fig9: the returns, vantage points and lines of the first K sonar feature initialisations\n"
    "      (map-frame, estimated poses) over the true walls, like the paper's Fig. 9, in the\n"
    "      corridor of mc. --phantoms 1: only lines farther than 0.25 m or 10 deg from every\n"
    "      wall (mc's count); --minutes M: how long to drive for them.\n";

using Args = eval::ToolOptions;
using eval::GetIntegerOption;
using eval::GetNumberOption;

// The largest --seed (seeds S..S+N-1 are printed as int).
constexpr int kMaxSeed = 1000000000;

// One simulated corridor run, stepped by the caller.
struct CorridorRun {
  std::vector<sim::Wall> walls;
  sim::RayCaster caster;
  WheelOdometryNoiseOptions wheel;
  sim::LaserOptions laser;
  sim::SonarOptions sonar;
  WheelOdometryModel odometry;
  sim::LaserModel scanner;
  sim::SonarModel ring_model;
  sim::DiffDriveFollower follower;

  static std::vector<sim::Wall> Walls() { return sim::CorridorWalls(20.0, 2.4); }
  static WheelOdometryNoiseOptions Wheel() {
    WheelOdometryNoiseOptions w;
    w.left_scale_error = w.right_scale_error = w.track_width_error = 0.0;
    return w;
  }
  static sim::LaserOptions Laser() {
    sim::LaserOptions l;
    l.beams = 361;
    return l;
  }
  static sim::SonarOptions Sonar(int ring) {
    sim::SonarOptions s;
    s.ring = ring == 16 ? sim::P3dxSonarRing() : sim::B21SonarRing();
    return s;
  }
  static std::vector<Vec2> Waypoints() {
    std::vector<Vec2> w;
    for (int lap = 0; lap < 40; ++lap) {
      for (int i = 0; i <= 6; ++i) {
        const int k = lap % 2 == 0 ? i : 6 - i;
        w.push_back(Vec2(1.0 + 3.0 * k, (k % 2 == 0 ? 0.25 : -0.25)));
      }
    }
    return w;
  }
  static sim::MotionOptions Motion() {
    sim::MotionOptions m;
    m.max_speed = 0.6;
    return m;
  }

  CorridorRun(uint64_t seed, int ring)
      : walls(Walls()),
        caster(walls),
        wheel(Wheel()),
        laser(Laser()),
        sonar(Sonar(ring)),
        odometry(wheel, seed * 7919 + 1),
        scanner(laser, seed * 104729 + 3),
        ring_model(sonar, seed * 15485863 + 5),
        follower(Motion(), Waypoints()) {}
};

struct Step {
  Pose2 truth, sonar, laser, odometry;
  double sonar_nees = 0.0, laser_nees = 0.0;
};

// One sonar line at its initialisation against the true wall nearest in (rho, alpha): NEES of
// the line (2 dof) and of the robot pose and the line jointly (5 dof).
struct InitNees {
  double line = 0.0, joint = 0.0;
  bool gross = false;  // more than 0.25 m or 10 degrees off that wall: a phantom or wrong wall
};

InitNees NeesAtInitialisation(const SonarLocalMap& map, int k, const Pose2& truth,
                              const std::vector<sim::Wall>& walls, const Pose2& origin) {
  const Eigen::VectorXd& x = map.Ekf().State();
  const Eigen::MatrixXd& p = map.Ekf().Covariance();
  const int ik = 3 + 2 * k;
  double rho = x(ik), alpha = x(ik + 1);
  CanonicalizeLine(rho, alpha);
  Vec2 best(0.0, 0.0);
  double best_d = 1e300;
  for (const Vec2& w : sonar_eval::WallLinesInFrame(walls, origin)) {
    const double dist = std::abs(w.x() - rho) + std::abs(WrapAngle(w.y() - alpha));
    if (dist < best_d) {
      best_d = dist;
      best = w;
    }
  }
  Eigen::Matrix<double, 5, 1> e;
  e << x(0) - truth.x, x(1) - truth.y, WrapAngle(x(2) - truth.theta), rho - best(0),
      WrapAngle(alpha - best(1));
  Eigen::Matrix<double, 5, 5> c;
  c << p.topLeftCorner<3, 3>(), p.block<3, 2>(0, ik), p.block<2, 3>(ik, 0), p.block<2, 2>(ik, ik);
  if (rho != x(ik)) {  // flipped to canonical: rho changes sign
    c.row(3) *= -1.0;
    c.col(3) *= -1.0;
  }
  c.topLeftCorner<3, 3>() += Vec3(sonar_eval::kNeesFloorM * sonar_eval::kNeesFloorM,
                                  sonar_eval::kNeesFloorM * sonar_eval::kNeesFloorM,
                                  sonar_eval::kNeesFloorRad * sonar_eval::kNeesFloorRad)
                                 .asDiagonal();
  InitNees out;
  const Vec2 el = e.tail<2>();
  out.gross = std::abs(el(0)) > 0.25 || std::abs(el(1)) > 10.0 * std::numbers::pi / 180.0;
  out.line = el.dot(c.bottomRightCorner<2, 2>().ldlt().solve(el));
  out.joint = e.dot(c.ldlt().solve(e));
  return out;
}

// The sonar map switches the tools take for comparison (--delayed-states, --point-rival,
// --init-edge-echoes, --extent-gap, --model-sigma).
struct MapSwitches {
  int delayed_states = SonarInitOptions().delayed_states ? 1 : 0,
      point_rival = SonarInitOptions().point_rival ? 1 : 0,
      edge_echoes = SonarInitOptions().edge_echoes ? 1 : 0;
  double extent_gap = SonarUpdateOptions().max_extent_gap,
         model_sigma = SonarModelOptions().model_sigma;

  bool Parse(const Args& args, std::string& error) {
    return GetIntegerOption(args, "--delayed-states", 0, 1, delayed_states, error) &&
           GetIntegerOption(args, "--point-rival", 0, 1, point_rival, error) &&
           GetIntegerOption(args, "--init-edge-echoes", 0, 1, edge_echoes, error) &&
           GetNumberOption(args, "--extent-gap", 0, 100, extent_gap, error) &&
           GetNumberOption(args, "--model-sigma", 0, 1, model_sigma, error);
  }
  void Apply(SonarLocalMapOptions& o) const {
    o.init.delayed_states = delayed_states != 0;
    o.init.point_rival = point_rival != 0;
    o.init.edge_echoes = edge_echoes != 0;
    o.update.max_extent_gap = extent_gap;
    o.model.model_sigma = model_sigma;
  }
};

std::vector<Step> RunOnce(uint64_t seed, double minutes, int ring, int capacity,
                          const MapSwitches& switches, int& sonar_lines, int& laser_lines,
                          std::vector<InitNees>& init_nees) {
  CorridorRun run(seed, ring);
  SonarLocalMapOptions sonar_o =
      sonar_eval::SimulatedMapOptions(RangeSensors::kSonar, capacity, run.wheel, run.sonar);
  switches.Apply(sonar_o);
  SonarLocalMap sonar(sonar_o);
  SonarLocalMap laser(
      sonar_eval::SimulatedMapOptions(RangeSensors::kLaser, capacity, run.wheel, run.sonar));
  const double dt = 0.02;
  const int steps = static_cast<int>(minutes * 60.0 / dt);
  const Pose2 origin = run.follower.pose();
  Pose2 last_odo = run.odometry.Step(TruthSample{Time{}, origin}).pose;
  const Pose2 odo_origin = last_odo;
  std::vector<Step> out;
  for (int s = 1; s <= steps; ++s) {
    run.follower.Step(dt);
    const Pose2 world = run.follower.pose();
    const Pose2 odo = run.odometry.Step(TruthSample{FromSeconds(s * dt), world}).pose;
    const Pose2 u = Between(last_odo, odo);
    sonar.Predict(u);
    laser.Predict(u);
    last_odo = odo;
    if (s % 5 != 0) continue;  // 10 Hz sonar readings and laser scans
    const Time stamp = FromSeconds(s * dt);
    const SonarUpdate up =
        sonar.UpdateSonar(run.ring_model.Read(run.caster, world, stamp), run.sonar.ring, true);
    laser.Update(run.scanner.Scan(run.caster, world, stamp), true);
    Step st;
    st.truth = Between(origin, world);
    for (int k = sonar.Complexity() - up.added; k < sonar.Complexity(); ++k) {
      init_nees.push_back(NeesAtInitialisation(sonar, k, st.truth, run.walls, origin));
    }
    st.sonar = sonar.RobotPose().mean;
    st.laser = laser.RobotPose().mean;
    st.odometry = Between(odo_origin, odo);
    st.sonar_nees = sonar_eval::PoseNees(sonar.RobotPose(), st.truth);
    st.laser_nees = sonar_eval::PoseNees(laser.RobotPose(), st.truth);
    out.push_back(st);
  }
  sonar_lines = sonar.Complexity();
  laser_lines = laser.Complexity();
  return out;
}

void AddRelativeErrors(const std::vector<Step>& steps, int gap, Pose2 Step::*which,
                       std::vector<double>& trans, std::vector<double>& rot) {
  for (size_t i = 0; i + gap < steps.size(); i += gap) {
    const Pose2 t = Between(steps[i].truth, steps[i + gap].truth);
    const Pose2 e = Between(steps[i].*which, steps[i + gap].*which);
    trans.push_back(std::hypot(t.x - e.x, t.y - e.y));
    rot.push_back(std::abs(WrapAngle(t.theta - e.theta)) * 180.0 / std::numbers::pi);
  }
}

int RunMonteCarlo(const Args& args) {
  double minutes = 3;
  int runs = 20, ring = 24, seed = 1, capacity = 20;
  MapSwitches switches;
  std::string error;
  if (!GetIntegerOption(args, "--runs", 1, 10000, runs, error) || !switches.Parse(args, error) ||
      !GetNumberOption(args, "--minutes", 0.05, 600, minutes, error) ||
      !GetIntegerOption(args, "--ring", 16, 24, ring, error) ||
      !GetIntegerOption(args, "--seed", 0, kMaxSeed, seed, error) ||
      !GetIntegerOption(args, "--capacity", 1, 1000, capacity, error)) {
    std::fprintf(stderr, "atlas-sonar-eval mc: %s\n", error.c_str());
    return 2;
  }
  if (ring != 16 && ring != 24) {
    std::fprintf(stderr, "atlas-sonar-eval mc: --ring must be 16 or 24\n");
    return 2;
  }
  const int n = static_cast<int>(runs);
  std::vector<std::vector<Step>> all;
  double sonar_lines = 0, laser_lines = 0;
  std::vector<InitNees> init_nees;
  for (int r = 0; r < n; ++r) {
    int sl = 0, ll = 0;
    all.push_back(RunOnce(static_cast<uint64_t>(seed) + r, minutes, static_cast<int>(ring),
                          static_cast<int>(capacity), switches, sl, ll, init_nees));
    sonar_lines += sl;
    laser_lines += ll;
    std::fprintf(stderr, "\rrun %d/%d done (%d sonar lines, %d laser lines)   ", r + 1, n, sl, ll);
  }
  std::fprintf(stderr, "\n");
  size_t steps = all[0].size();
  for (const auto& a : all) steps = std::min(steps, a.size());
  const double lo = ChiSquareQuantile(0.025, 3 * n) / n, hi = ChiSquareQuantile(0.975, 3 * n) / n;
  std::printf(
      "corridor 20 m x 2.4 m, %d runs x %.1f min, %d-transducer ring (specular misses, "
      "multipath), capacity %d; mean final lines: sonar %.1f, laser %.1f\n",
      n, minutes, static_cast<int>(ring), static_cast<int>(capacity), sonar_lines / n,
      laser_lines / n);
  for (const auto& [name, field] :
       {std::pair{"sonar-only", &Step::sonar_nees}, std::pair{"laser-only", &Step::laser_nees}}) {
    int inside = 0;
    double mean = 0.0, max = 0.0;
    for (size_t k = 0; k < steps; ++k) {
      double sum = 0.0;
      for (const auto& a : all) sum += a[k].*field;
      const double avg = sum / n;
      mean += avg;
      max = std::max(max, avg);
      inside += (avg >= lo && avg <= hi) ? 1 : 0;
    }
    std::printf(
        "  robot NEES %-10s: 95%% band [%.2f, %.2f]; mean %.2f, max %.2f; steps inside "
        "%d/%zu = %.1f%%, below the upper bound %.1f%%\n",
        name, lo, hi, mean / steps, max, inside, steps, 100.0 * inside / steps, [&] {
          int below = 0;
          for (size_t k = 0; k < steps; ++k) {
            double sum = 0.0;
            for (const auto& a : all) sum += a[k].*field;
            below += sum / n <= hi ? 1 : 0;
          }
          return 100.0 * below / steps;
        }());
  }
  {
    // Lines far from every wall are phantoms (corner and edge echoes) or a wrong wall, not a
    // covariance question: counted apart.
    std::vector<double> line, joint;
    int gross = 0, line_out = 0, joint_out = 0;
    const double line_hi = ChiSquareQuantile(0.95, 2), joint_hi = ChiSquareQuantile(0.95, 5);
    for (const InitNees& v : init_nees) {
      if (v.gross) {
        ++gross;
        continue;
      }
      line.push_back(v.line);
      joint.push_back(v.joint);
      line_out += v.line > line_hi ? 1 : 0;
      joint_out += v.joint > joint_hi ? 1 : 0;
    }
    const eval::ErrorStats ls = eval::Summarize(line), js = eval::Summarize(joint);
    const double k = std::max<double>(1.0, static_cast<double>(line.size()));
    std::printf(
        "  sonar lines at initialisation (%s): %zu within 0.25 m and 10 deg of their nearest "
        "wall (+%d farther); line NEES (2 dof) mean %.2f, above the 95%% bound %.1f%%; robot+line "
        "NEES (5 dof) mean %.2f, above the 95%% bound %.1f%%\n",
        switches.delayed_states != 0 ? "delayed states" : "independent vantage points", line.size(),
        gross, ls.mean, 100.0 * line_out / k, js.mean, 100.0 * joint_out / k);
  }
  for (const int gap_s : {5, 30, 90}) {
    if (static_cast<size_t>(gap_s * 10) >= steps) break;
    std::printf("  relative-pose errors, pairs %d s apart (all runs):\n", gap_s);
    for (const auto& [name, field] :
         {std::pair{"sonar-only", &Step::sonar}, std::pair{"laser-only", &Step::laser},
          std::pair{"dead reckoning", &Step::odometry}}) {
      std::vector<double> t, r;
      for (const auto& a : all) AddRelativeErrors(a, gap_s * 10, field, t, r);
      const eval::ErrorStats et = eval::Summarize(t), er = eval::Summarize(r);
      std::printf(
          "    %-15s: trans %.4f +- %.4f m (rmse %.4f, max %.3f), rot %.3f +- %.3f deg "
          "(max %.2f), %lld pairs\n",
          name, et.mean, et.stddev, et.rmse, et.max, er.mean, er.stddev, er.max,
          static_cast<long long>(et.count));
    }
  }
  return 0;
}

void Arc(draw::Canvas& c, const Pose2& sensor, double range, double half, const draw::Stroke& s) {
  std::vector<Vec2> pts;
  for (int i = 0; i <= 12; ++i) {
    const double a = sensor.theta - half + 2.0 * half * i / 12.0;
    pts.push_back(Vec2(sensor.x + range * std::cos(a), sensor.y + range * std::sin(a)));
  }
  c.Polyline(pts, s);
}

int RunFig9(const Args& args) {
  int ring = 24, seed = 1, lines = 4, phantoms = 0;
  double minutes = 3;
  std::string error;
  if (!GetIntegerOption(args, "--ring", 16, 24, ring, error) ||
      !GetIntegerOption(args, "--seed", 0, kMaxSeed, seed, error) ||
      !GetIntegerOption(args, "--lines", 1, 20, lines, error) ||
      !GetIntegerOption(args, "--phantoms", 0, 1, phantoms, error) ||
      !GetNumberOption(args, "--minutes", 0.1, 600, minutes, error)) {
    std::fprintf(stderr, "atlas-sonar-eval fig9: %s\n", error.c_str());
    return 2;
  }
  const std::string png = args.values.count("--png") ? args.values.at("--png") : "sonar_fig9.png";
  draw::ImageFormat format;
  if (!draw::ImageFormatOf(png, &format)) {
    std::fprintf(stderr, "atlas-sonar-eval fig9: --png must end in .png or .svg\n");
    return 2;
  }
  CorridorRun run(static_cast<uint64_t>(seed), static_cast<int>(ring));
  SonarLocalMap map(
      sonar_eval::SimulatedMapOptions(RangeSensors::kSonar, 20, run.wheel, run.sonar));
  struct Drawn {
    Pose2 robot;
    InitialisedLine line;
  };
  std::vector<Drawn> drawn;
  std::vector<Vec2> path, true_path;
  const Pose2 origin = run.follower.pose();
  Pose2 last_odo = run.odometry.Step(TruthSample{Time{}, origin}).pose;
  const double dt = 0.02;
  const std::vector<Vec2> wall_lines = sonar_eval::WallLinesInFrame(run.walls, origin);
  for (int s = 1; s <= minutes * 60 * 50 && static_cast<int>(drawn.size()) < lines; ++s) {
    run.follower.Step(dt);
    const Pose2 world = run.follower.pose();
    const Pose2 odo = run.odometry.Step(TruthSample{FromSeconds(s * dt), world}).pose;
    map.Predict(Between(last_odo, odo));
    last_odo = odo;
    if (s % 5 != 0) continue;
    const SonarUpdate up = map.UpdateSonar(
        run.ring_model.Read(run.caster, world, FromSeconds(s * dt)), run.sonar.ring, true);
    const Pose2 est = map.RobotPose().mean;
    path.push_back(Vec2(est.x, est.y));
    const Pose2 t = Between(origin, world);
    true_path.push_back(Vec2(t.x, t.y));
    for (const InitialisedLine& l : up.initialised) {
      if (phantoms != 0) {
        const Vec2 seen = sonar_eval::WallLine(sim::Wall{est.TransformPoint(l.line.endpoint_a),
                                                         est.TransformPoint(l.line.endpoint_b)});
        if (!sonar_eval::FarFromEveryWall(seen, wall_lines)) continue;
      }
      drawn.push_back(Drawn{est, l});
    }
  }
  if (drawn.empty()) {
    std::fprintf(stderr, "atlas-sonar-eval fig9: no %s was initialised in %.1f minutes\n",
                 phantoms != 0 ? "phantom line" : "line", minutes);
    return 1;
  }
  Vec2 lo(-1, -2.5), hi(21, 2.5);
  std::string err;
  const draw::ViewTransform view = draw::ViewTransform::Fit(lo, hi, 10, 60, 1780, 520);
  auto canvas = draw::Canvas::Create(format, png, 1800, 640, view, &err);
  if (!canvas) {
    std::fprintf(stderr, "atlas-sonar-eval fig9: %s\n", err.c_str());
    return 1;
  }
  for (const sim::Wall& w : run.walls) {
    canvas->Line(Inverse(origin).TransformPoint(w.a), Inverse(origin).TransformPoint(w.b),
                 draw::Stroke{draw::Color{0.7, 0.7, 0.7, 1.0}, 6.0, false});
  }
  canvas->Polyline(true_path, draw::Stroke{draw::Color{0.3, 0.7, 0.3, 1.0}, 1.5, false});
  canvas->Polyline(path, draw::Stroke{draw::Color{0.1, 0.4, 0.9, 1.0}, 1.5, false});
  const draw::Color palette[4] = {
      {0.85, 0.1, 0.1, 1.0}, {0.6, 0.1, 0.7, 1.0}, {0.9, 0.5, 0.0, 1.0}, {0.0, 0.55, 0.55, 1.0}};
  for (size_t i = 0; i < drawn.size(); ++i) {
    const Drawn& d = drawn[i];
    const draw::Color col = palette[i % 4];
    const double half = 0.5 * run.sonar.ring[0].beam_width;
    for (size_t j = 0; j < d.line.sensors.size(); ++j) {
      const Pose2 sensor = Compose(d.robot, d.line.sensors[j]);
      Arc(*canvas, sensor, d.line.ranges[j], half, draw::Stroke{col.WithAlpha(0.45), 1.0, false});
      canvas->FilledCircle(d.robot.TransformPoint(d.line.tangent_points[j]), 2.5, col);
    }
    for (const Pose2& v : d.line.vantage)
      canvas->Pose(Compose(d.robot, v), 0.12, col.WithAlpha(0.8));
    canvas->Line(d.robot.TransformPoint(d.line.line.endpoint_a),
                 d.robot.TransformPoint(d.line.line.endpoint_b), draw::Stroke{col, 4.0, false});
    std::printf(
        "line %zu: %d returns from %zu vantage points over %.2f m baseline; sigma rho "
        "%.3f m, sigma alpha %.2f deg\n",
        i + 1, d.line.support, d.line.vantage.size(), d.line.baseline,
        std::sqrt(d.line.line.cov(0, 0)),
        std::sqrt(d.line.line.cov(1, 1)) * 180.0 / std::numbers::pi);
  }
  char title[200];
  std::snprintf(title, sizeof(title),
                "Sonar feature initialisation from several vantage points (%d-transducer ring, "
                "seed %d): first %zu %s",
                static_cast<int>(ring), static_cast<int>(seed), drawn.size(),
                phantoms != 0 ? "phantom lines (0.25 m or 10 deg off every wall)" : "lines");
  canvas->TextPx(Vec2(12, 28), title, 20, draw::Color{}, true);
  canvas->ScaleBar();
  canvas->Legend(
      Vec2(12, 630),
      {{"true walls", {0.7, 0.7, 0.7, 1}, false},
       {"true / estimated path", {0.1, 0.4, 0.9, 1}, false},
       {"returns (arcs), tangent points, vantage poses, line", {0.85, 0.1, 0.1, 1}, false}});
  const std::string fin = canvas->Finish();
  if (!fin.empty()) {
    std::fprintf(stderr, "atlas-sonar-eval fig9: %s\n", fin.c_str());
    return 1;
  }
  std::printf("wrote %s\n", png.c_str());
  return 0;
}

// --world: atlas-sim's building (R rooms, layout from the seed) or the alcove loop.
std::string SelectWorld(const std::string& name, int seed, int rooms,
                        const sonar_eval::AlcoveLoopOptions& loop, sim::World* world) {
  if (name == "building") {
    sim::BuildingOptions bo;
    bo.min_rooms = static_cast<int>(rooms);
    *world = sim::GenerateBuilding(bo, static_cast<uint64_t>(seed));
    return "";
  }
  if (name == "alcoves") {
    if (std::string e = loop.Validate(); !e.empty()) return "alcove loop: " + e;
    *world = sonar_eval::AlcoveLoopWorld(loop);
    return "";
  }
  return "--world must be 'building' or 'alcoves', not '" + name + "'";
}

// ---- atlas mode: sonar-only and laser-only atlases on simulated runs ----

// Mean over runs of the per-step NEES (steps where every run has a value), against the 95 %
// band of chi-square(3 runs) / runs, as atlas-localmap-eval mc does for one map.
void PrintNeesBand(const char* name, const std::vector<sonar_eval::AtlasRunReport>& runs) {
  size_t steps = runs[0].nees.size();
  for (const auto& r : runs) steps = std::min(steps, r.nees.size());
  const int n = static_cast<int>(runs.size());
  const double lo = ChiSquareQuantile(0.025, 3 * n) / n, hi = ChiSquareQuantile(0.975, 3 * n) / n;
  int used = 0, inside = 0, below = 0;
  double mean = 0.0, max = 0.0;
  for (size_t k = 0; k < steps; ++k) {
    double sum = 0.0;
    bool known = true;
    for (const auto& r : runs) {
      known &= r.nees[k] >= 0.0;
      sum += r.nees[k];
    }
    if (!known) continue;
    const double avg = sum / n;
    ++used;
    mean += avg;
    max = std::max(max, avg);
    inside += avg >= lo && avg <= hi;
    below += avg <= hi;
  }
  std::printf(
      "  robot NEES %s (dominant pose in its frame, mean over %d runs per step): 95%% band "
      "[%.3f, %.3f]; mean %.2f, max %.1f; steps inside %d/%d = %.1f%%, below the upper bound "
      "%.1f%%\n",
      name, n, lo, hi, used ? mean / used : 0.0, max, inside, used,
      used ? 100.0 * inside / used : 0.0, used ? 100.0 * below / used : 0.0);
}

void PrintMatches(const char* name, const std::vector<sonar_eval::AtlasRunReport>& runs) {
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

void PrintAtlasErrors(const char* name, const std::vector<sonar_eval::AtlasRunReport>& runs,
                      int gap, bool dr) {
  std::vector<double> tr, rot;
  int skipped = 0;
  for (const auto& t : runs) {
    for (size_t i = 0; i + gap < t.truth.size(); i += gap) {
      if (!dr && t.frame[i] != t.frame[i + gap]) {
        ++skipped;
        continue;
      }
      const Pose2 a = Between(t.truth[i], t.truth[i + gap]);
      const Pose2 b = dr ? Between(t.odometry[i], t.odometry[i + gap])
                         : Between(t.estimate[i], t.estimate[i + gap]);
      tr.push_back(std::hypot(a.x - b.x, a.y - b.y));
      rot.push_back(std::abs(WrapAngle(a.theta - b.theta)) * 180.0 / std::numbers::pi);
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
      if (in_frame.empty()) in_frame = sonar_eval::WallLinesInFrame(*walls, *origin[h.frame]);
      double worst = 0.0;
      int off = 0;
      for (const MapLine& l : map.Lines()) {
        const double nees = sonar_eval::NeesAgainstNearestWall(l, in_frame);
        worst = std::max(worst, nees);
        off += nees > kLineOffNees ? 1 : 0;
      }
      std::fprintf(
          f,
          "%d\t%.2f\t%lld\t%d\t%s\t%d\t%.3f\t%.2f\t%.3f\t%.3f\t%.4f\t%.3f\t%.3f\t%.4f\t%d\t"
          "%d\t%d\t%d\t%d\t%.1f\t%d\n",
          run, ToSeconds(stamp), static_cast<long long>(h.id), h.frame,
          HypothesisStateName(h.state), h.dominant ? 1 : 0, h.q, sonar_eval::PoseNees(p, t),
          p.mean.x - t.x, p.mean.y - t.y, WrapAngle(p.mean.theta - t.theta), std::sqrt(p.cov(0, 0)),
          std::sqrt(p.cov(1, 1)), std::sqrt(p.cov(2, 2)), h.last_update.observations,
          h.last_update.matched, h.last_update.added,
          atlas.Graph().Frame(h.frame).map->Complexity(), h.bootstrapped ? 1 : 0, worst, off);
    }
  }
};

int RunAtlasMode(const Args& args) {
  const AtlasOptions sonar_defaults = sonar_eval::SonarAtlasOptions();
  int ring = 24, seed = 1, rooms = 6, capacity = 10, runs = 1, laser = 1, self_match = 1,
      edge_extent = 1, keep_frame_map = 0, sonar_w = 1,
      w_edge_echoes = SonarBootstrapOptions().edge_echoes ? 1 : 0,
      w_dead_reckoned = SonarBootstrapOptions().dead_reckoned_start ? 1 : 0,
      bootstrap_steps = sonar_defaults.lifecycle.bootstrap_scans, probation = -1,
      line_correlation = sonar_eval::SonarAtlasOptions().match.unknown_line_correlation ? 1 : 0;
  double km = 0.4, seed_scale = 1,
         redundancy = sonar_eval::SonarAtlasOptions().match.redundancy_sigma,
         redundancy_prior = sonar_eval::SonarAtlasOptions().match.redundancy_prior_halfwidth,
         alternative = sonar_eval::SonarAtlasOptions().match.alternative_sigmas;
  sonar_eval::AlcoveLoopOptions loop;
  MapSwitches switches;
  std::string error;
  if (!GetIntegerOption(args, "--ring", 16, 24, ring, error) ||
      !GetIntegerOption(args, "--seed", 0, kMaxSeed, seed, error) ||
      !GetNumberOption(args, "--km", 0.01, 100, km, error) ||
      !GetIntegerOption(args, "--rooms", 1, 10000, rooms, error) ||
      !GetIntegerOption(args, "--capacity", 2, 100, capacity, error) ||
      !GetIntegerOption(args, "--runs", 1, 1000, runs, error) ||
      !GetIntegerOption(args, "--laser", 0, 1, laser, error) ||
      !GetIntegerOption(args, "--self-match", 0, 1, self_match, error) ||
      !switches.Parse(args, error) ||
      !GetIntegerOption(args, "--edge-extent", 0, 1, edge_extent, error) ||
      !GetNumberOption(args, "--redundancy-sigma", 0, 100, redundancy, error) ||
      !GetIntegerOption(args, "--line-correlation", 0, 1, line_correlation, error) ||
      !GetIntegerOption(args, "--keep-frame-map", 0, 1, keep_frame_map, error) ||
      !GetNumberOption(args, "--seed-cov-scale", 1, 100, seed_scale, error) ||
      !GetIntegerOption(args, "--sonar-w", 0, 1, sonar_w, error) ||
      !GetIntegerOption(args, "--w-edge-echoes", 0, 1, w_edge_echoes, error) ||
      !GetIntegerOption(args, "--w-dead-reckoned", 0, 1, w_dead_reckoned, error) ||
      !GetIntegerOption(args, "--bootstrap-steps", 1, 1000, bootstrap_steps, error) ||
      !GetIntegerOption(args, "--probation", 2, 1000, probation, error) ||
      !GetNumberOption(args, "--redundancy-prior", 0, 100, redundancy_prior, error) ||
      !GetNumberOption(args, "--alternative-sigmas", 0, 100, alternative, error) ||
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
  const std::string world_name =
      args.values.count("--world") ? args.values.at("--world") : "building";
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
  std::vector<sonar_eval::AtlasRunReport> sonar_runs, laser_runs;
  sim::SimulationSummary sum;
  for (int r = 0; r < n; ++r) {
    sim::SimulationOptions so;
    so.length_m = km * 1000.0;
    so.laser = laser != 0;
    so.sonar = true;
    so.sonar_options = CorridorRun::Sonar(static_cast<int>(ring));
    so.seed = static_cast<uint64_t>(seed) + r;
    if (std::string e = so.Validate(); !e.empty()) {
      std::fprintf(stderr, "atlas-sonar-eval atlas: simulation options: %s\n", e.c_str());
      return 2;
    }
    sonar_eval::SimRecording rec;
    sum = sim::Simulate(world, so, rec, [&](double d) {
      std::fprintf(stderr, "\rrun %d/%d: simulated %.0f m   ", r + 1, n, d);
    });
    if (!sum.error.empty() || rec.Empty()) {
      std::fprintf(stderr, "\natlas-sonar-eval atlas: simulation failed: %s\n", sum.error.c_str());
      return 1;
    }
    SonarLocalMapOptions sonar_o = sonar_eval::SimulatedMapOptions(
        RangeSensors::kSonar, static_cast<int>(capacity), so.odometry_options, so.sonar_options);
    switches.Apply(sonar_o);
    sonar_o.update.edge_extent_footprint = edge_extent != 0;
    if (std::string e = sonar_o.Validate(); !e.empty()) {
      std::fprintf(stderr, "\natlas-sonar-eval atlas: sonar map options: %s\n", e.c_str());
      return 2;
    }
    AtlasOptions ao = sonar_eval::SonarAtlasOptions();
    ao.match.self_match = self_match != 0;
    ao.match.redundancy_sigma = redundancy;
    ao.match.redundancy_prior_halfwidth = redundancy_prior;
    ao.match.alternative_sigmas = alternative;
    ao.match.unknown_line_correlation = line_correlation != 0;
    ao.keep_frame_map_without_w = keep_frame_map != 0;
    ao.seed_cov_scale_without_w = seed_scale;
    ao.lifecycle.bootstrap_scans = static_cast<int>(bootstrap_steps);
    ao.lifecycle.probation_scans =
        probation > 0 ? static_cast<int>(probation)
        : sonar_w != 0
            ? std::max(sonar_defaults.lifecycle.probation_scans, kSonarBootstrapProbation)
            : sonar_defaults.lifecycle.probation_scans;
    if (std::string e = ao.Validate(); !e.empty()) {
      std::fprintf(stderr, "\natlas-sonar-eval atlas: sonar atlas options: %s\n", e.c_str());
      return 2;
    }
    AtlasOptions laser_ao;
    laser_ao.match.self_match = self_match != 0;
    std::shared_ptr<const PoseBootstrapper> sonar_bootstrapper;
    SonarBootstrapOptions wo;
    wo.edge_echoes = w_edge_echoes != 0;
    wo.dead_reckoned_start = w_dead_reckoned != 0;
    if (sonar_w != 0) sonar_bootstrapper = std::make_shared<SonarMapBootstrapper>(wo);
    Atlas sonar_atlas(
        ao, [sonar_o]() { return std::make_unique<SonarLocalMap>(sonar_o); }, sonar_bootstrapper);
    TraceWriter tw{trace, r + 1, &world.walls, {}};
    sonar_runs.push_back(sonar_eval::RunAtlas(
        sonar_atlas, rec, true,
        [&](double f) {
          std::fprintf(stderr, "\rrun %d/%d: sonar atlas %.0f%%   ", r + 1, n, 100 * f);
        },
        trace ? [&](const Atlas& a, Time t, const Pose2& truth,
                    const std::vector<std::optional<Pose2>>& o) { tw.Row(a, t, truth, o); }
              : sonar_eval::StepObserver{}));
    if (laser != 0) {
      const LocalMapOptions lm =
          sonar_eval::SimulatedMapOptions(RangeSensors::kLaser, static_cast<int>(capacity),
                                          so.odometry_options, so.sonar_options)
              .line_map;
      Atlas laser_atlas(
          laser_ao, [lm]() { return std::make_unique<LineEkfMap>(lm); },
          std::make_shared<LineMapBootstrapper>(lm));
      laser_runs.push_back(sonar_eval::RunAtlas(laser_atlas, rec, false, [&](double f) {
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

// ---- assoc mode: the sonar map's data association against the simulator's truth ----

// The wall whose echo the transducer at `sensor` (world) reports, as the simulator decides it
// (sim SonarModel::Fire: nearest ray of the cone meeting a wall within the critical
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

int RunAssocMode(const Args& args) {
  int ring = 24, seed = 1, capacity = 40, show = 10;
  double km = 0.15;
  sonar_eval::AlcoveLoopOptions loop;
  std::string error;
  if (!GetIntegerOption(args, "--ring", 16, 24, ring, error) ||
      !GetIntegerOption(args, "--seed", 0, kMaxSeed, seed, error) ||
      !GetNumberOption(args, "--km", 0.01, 100, km, error) ||
      !GetIntegerOption(args, "--capacity", 2, 200, capacity, error) ||
      !GetIntegerOption(args, "--show", 0, 1000, show, error)) {
    std::fprintf(stderr, "atlas-sonar-eval assoc: %s\n", error.c_str());
    return 2;
  }
  const std::string world_name =
      args.values.count("--world") ? args.values.at("--world") : "alcoves";
  sim::World world;
  if (std::string e = SelectWorld(world_name, seed, 6, loop, &world); !e.empty()) {
    std::fprintf(stderr, "atlas-sonar-eval assoc: %s\n", e.c_str());
    return 2;
  }
  sim::SimulationOptions so;
  so.length_m = km * 1000.0;
  so.laser = false;
  so.sonar = true;
  so.sonar_options = CorridorRun::Sonar(static_cast<int>(ring));
  so.seed = static_cast<uint64_t>(seed);
  sonar_eval::SimRecording rec;
  const sim::SimulationSummary sum = sim::Simulate(world, so, rec);
  if (!sum.error.empty()) {
    std::fprintf(stderr, "atlas-sonar-eval assoc: simulation failed: %s\n", sum.error.c_str());
    return 1;
  }
  const sim::RayCaster caster(world.walls);
  SonarLocalMap map(sonar_eval::SimulatedMapOptions(
      RangeSensors::kSonar, static_cast<int>(capacity), so.odometry_options, so.sonar_options));
  const auto& ring_mounts = so.sonar_options.ring;
  bool first = true;
  Pose2 last_odo, origin;
  std::vector<Vec2> wall_lines;  // in the map frame, index = the caster's wall index
  int counts[2][3] = {};         // [edge][correct, wrong line, no echo]
  int shown = 0;
  double next_print = 0.0;
  for (const sonar_eval::SimRecording::Event& e : rec.Events()) {
    if (!e.sonar) continue;
    const Pose2 truth = rec.TruthAt(e.stamp);
    if (first) {
      origin = truth;
      last_odo = e.odometry;
      wall_lines = sonar_eval::WallLinesInFrame(world.walls, origin);
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
                  sonar_eval::PoseNees(map.RobotPose(), Between(origin, truth)), map.Complexity());
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
}  // namespace atlas

int main(int argc, char** argv) {
  if (argc < 2 || std::strcmp(argv[1], "--help") == 0 || std::strcmp(argv[1], "-h") == 0) {
    std::fputs(atlas::kUsage, argc < 2 ? stderr : stdout);
    return argc < 2 ? 2 : 0;
  }
  const std::string cmd = argv[1];
  if (cmd == "mc") {
    const atlas::Args a = atlas::eval::ParseToolOptions(
        argc, argv, 2,
        {"--runs", "--minutes", "--ring", "--seed", "--capacity", "--delayed-states",
         "--point-rival", "--init-edge-echoes", "--extent-gap", "--model-sigma"});
    if (!a.error.empty()) {
      std::fprintf(stderr, "atlas-sonar-eval mc: %s\n%s", a.error.c_str(), atlas::kUsage);
      return 2;
    }
    return atlas::RunMonteCarlo(a);
  }
  if (cmd == "atlas") {
    // clang-format off
    const atlas::Args a = atlas::eval::ParseToolOptions(
        argc, argv, 2,
        {"--world", "--ring", "--seed", "--runs", "--km", "--rooms", "--capacity", "--laser",
         "--trace", "--self-match", "--period", "--loop-length", "--loop-width", "--delayed-states",
         "--edge-extent", "--redundancy-sigma", "--line-correlation", "--redundancy-prior",
         "--keep-frame-map", "--seed-cov-scale", "--sonar-w", "--bootstrap-steps", "--probation",
         "--w-edge-echoes", "--point-rival", "--init-edge-echoes", "--alternative-sigmas",
         "--extent-gap", "--model-sigma", "--w-dead-reckoned"});
    // clang-format on
    if (!a.error.empty()) {
      std::fprintf(stderr, "atlas-sonar-eval atlas: %s\n%s", a.error.c_str(), atlas::kUsage);
      return 2;
    }
    return atlas::RunAtlasMode(a);
  }
  if (cmd == "assoc") {
    const atlas::Args a = atlas::eval::ParseToolOptions(
        argc, argv, 2, {"--world", "--ring", "--seed", "--km", "--capacity", "--show"});
    if (!a.error.empty()) {
      std::fprintf(stderr, "atlas-sonar-eval assoc: %s\n%s", a.error.c_str(), atlas::kUsage);
      return 2;
    }
    return atlas::RunAssocMode(a);
  }
  if (cmd == "fig9") {
    const atlas::Args a = atlas::eval::ParseToolOptions(
        argc, argv, 2, {"--png", "--ring", "--seed", "--lines", "--phantoms", "--minutes"});
    if (!a.error.empty()) {
      std::fprintf(stderr, "atlas-sonar-eval fig9: %s\n%s", a.error.c_str(), atlas::kUsage);
      return 2;
    }
    return atlas::RunFig9(a);
  }
  std::fprintf(stderr, "atlas-sonar-eval: unknown command '%s'\n%s", cmd.c_str(), atlas::kUsage);
  return 2;
}
