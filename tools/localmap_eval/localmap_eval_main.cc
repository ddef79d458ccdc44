// atlas-localmap-eval: evaluation of the line-feature EKF local map (issue 3).
//
//   atlas-localmap-eval mc   [--runs N] [--minutes M] [--seed S] [--capacity C]
//       Monte Carlo consistency in a simulated corridor (sim ray caster, laser and
//       wheel-odometry models): average NEES of the robot pose and of the features per step
//       against the 95 % chi-square band.
//   atlas-localmap-eval real [--log F] [--relations F] [--stretch M] [--capacity C] [--png F]
//                            [--laser-time-offset S]
//       mit-csail: one local map per stretch of M metres of travel (no Genesis), scored on the
//       relations whose two poses lie in one stretch, against dead reckoning on the same ones;
//       optionally draws one local map over its scans. With a laser time offset the filter's
//       odometry is interpolated at each scan's stamp + S (daemon/atlasd/step_loop.h).
//       Dead reckoning is the log's odometry at the relation stamps (and, with an offset, also
//       the odometry at stamp + S).

#include <Eigen/Cholesky>
#include <Eigen/Eigenvalues>
#include <Eigen/LU>
#include <algorithm>
#include <cerrno>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <map>
#include <random>
#include <string>
#include <vector>

#include "core/common/parse_number.h"
#include "core/eval/error_stats.h"
#include "core/eval/relations_metric.h"
#include "core/localmap/jcbb.h"
#include "core/localmap/line_ekf_map.h"
#include "core/localmap/line_model.h"
#include "core/scanmatch/scan_matcher.h"
#include "daemon/atlasd/odometry_track.h"
#include "logs/carmen/carmen_log.h"
#include "sim/corridor.h"
#include "sim/laser_model.h"
#include "sim/ray_caster.h"
#include "sim/route.h"
#include "sim/wheel_odometry_model.h"
#include "tools/eval/tool_options.h"
#include "tools/eval/trajectory_files.h"
#include "tools/render/canvas.h"

namespace atlas {
namespace {

constexpr char kUsage[] =
    "usage: atlas-localmap-eval mc   [--runs N=50] [--minutes M=4] [--seed S=1] [--capacity C=20]\n"
    "                                [--calibration fixed|per-run|off] [--per-run 0|1] [--dump F]\n"
    "                                [--set name=v,...]\n"
    "       atlas-localmap-eval real [--log F] [--relations F] [--stretch M=30] [--capacity "
    "C=100]\n"
    "                                [--png F] [--draw-stretch K=3] [--set name=v,...]\n"
    "                                [--laser-x X=0] [--laser-time-offset S=0] [--scan-match "
    "0|1=1]\n"
    "\n"
    "mc:   Monte Carlo consistency of the line EKF in a simulated 20 m corridor (seeded runs of\n"
    "      M minutes each). Prints the 95 % chi-square band of the average NEES (robot: 3 dof;\n"
    "      features: joint NEES per dof) and the fraction of steps inside it, and the\n"
    "      simulator's odometry errors whitened with the filter's Q (per 50 Hz step and per\n"
    "      scan interval). --calibration: the base's wheel-radius / track-width errors are the\n"
    "      simulator's defaults in every run (fixed), drawn per run from the filter's sigmas\n"
    "      (per-run), or absent and not modelled (off). --per-run 1 prints each run's NEES at\n"
    "      the first scan, mean, max; --dump F writes every run's per-scan NEES to F.\n"
    "      The filter's range sigma is the simulator's (1 cm) times 1.05: the margin for the\n"
    "      line fits' residual biases (docs/localmap.md, session 10). --set overrides filter\n"
    "      options as in real (--set range_sigma=0.01: the simulator's sigma exactly).\n"
    "real: mit-csail.clf.gz, one local map per stretch of M metres of travel, restarting at\n"
    "      each stretch (no Genesis). Scores the relations whose two poses lie in one stretch\n"
    "      and dead reckoning on the same relations. --png draws stretch K's map over its scans.\n"
    "      --laser-x: the laser X metres ahead of the robot's centre (the log's FLASER lines\n"
    "      give none). --set overrides filter options (a bad name lists them).\n"
    "      --laser-time-offset S: a scan was taken at its stamp + S seconds (-1..1; mit-csail:\n"
    "      about -0.1): the filter's odometry is interpolated there. Dead reckoning is the\n"
    "      log's odometry at the scan stamps (with S, also printed at stamp + S).\n"
    "      --scan-match 1 (default): the filter predicts with each scan matched against the one\n"
    "      before (core/scanmatch, atlasd's [scan_match] defaults) instead of the odometry\n"
    "      increment, as atlasd's loop does; 0: the odometry alone. Dead reckoning stays the\n"
    "      log's odometry.\n"
    "      Defaults: " ATLAS_SHARED_DIR "/datasets/mit-csail/mit-csail.clf.gz and .relations\n";

using Args = eval::ToolOptions;
using eval::GetIntegerOption;
using eval::GetNumberOption;

// Seeds S..S+runs-1 are printed as int.
constexpr int kMaxSeed = 1000000000;

// ---------------------------------------------------------------------------------------------
// Monte Carlo consistency.

struct StepNees {
  double robot = 0.0;
  double features = 0.0;
  int feature_dof = 0;
};

// The simulator's odometry errors against the filter's Q: each 50 Hz increment's true error
// whitened with Q(u) (OdometryNoise, rank 2: the two wheels), and each scan interval's error
// against the covariance the filter's own Predict() grows from zero over that interval. A
// filter whose noise model matches the simulator gives whitened errors of mean 0 and
// covariance I, and an interval NEES of mean 3.
struct OdometryCheck {
  long steps = 0;
  Eigen::Vector2d step_sum = Eigen::Vector2d::Zero();
  Eigen::Matrix2d step_ww = Eigen::Matrix2d::Zero();
  long intervals = 0;
  double interval_nees = 0.0;
  Eigen::Vector3d interval_sum = Eigen::Vector3d::Zero();
  Eigen::Matrix3d interval_ww = Eigen::Matrix3d::Zero();
  long interval_above95 = 0, interval_above99 = 0;        // NEES above the chi-square(3) quantiles
  long first_above95 = 0, first_above99 = 0, firsts = 0;  // the same for each run's first scan
};

// The filter's range sigma over the simulated laser's. The line fits of a straight wall keep
// biases of a few hundredths of their sigma (head-on: the fit's second-order bias; next to door
// jambs: the split's noise-dependent corner; docs/localmap.md, session 9) that repeat in every
// scan and add up over the thousands of fits fused into one feature. Five per cent more range
// noise covers them: over seeds 1-1000 the robot NEES averages 2.99 (3 dof) and the feature
// NEES 0.98 per dof, against 3.16 and 1.07 with the exact sigma (docs/localmap.md, session 10).
constexpr double kRangeSigmaMargin = 1.05;
constexpr double kSimRangeSigma = 0.01;  // the simulated laser's, metres

LocalMapOptions SimFilterOptions(int capacity, const WheelOdometryNoiseOptions& wheel,
                                 const sim::LaserOptions& laser) {
  LocalMapOptions o;
  o.capacity = capacity;
  o.extraction.range_sigma = laser.range_sigma * kRangeSigmaMargin;
  o.odometry.track_width = wheel.track_width_m;
  o.odometry.wheel_var_per_m = wheel.wheel_noise_per_m;
  o.odometry.xy_var_per_m = 0.0;
  o.odometry.xy_var_per_rad = 0.0;
  o.odometry.theta_var_per_m = 0.0;
  o.odometry.theta_var_per_rad = 0.0;
  // The simulated base's calibration errors (systematic, the same every step): their sizes are
  // the standard deviations of the filter's calibration model (OdometryNoiseOptions).
  o.odometry.wheel_scale_sigma =
      std::max(std::abs(wheel.left_scale_error), std::abs(wheel.right_scale_error));
  o.odometry.track_width_sigma = std::abs(wheel.track_width_error);
  return o;
}

// The true line of the wall most beams of an observation hit.
bool TrueLineOf(const ObservedLine& z, const Pose2& truth, const LaserScan& scan,
                const sim::RayCaster& caster, const std::vector<sim::Wall>& walls, Vec2& line) {
  std::map<int, int> votes;
  const Pose2 sensor = Compose(truth, scan.sensor_pose);
  for (int i = z.first_beam; i <= z.last_beam; ++i) {
    const double phi =
        sensor.theta + scan.angle_min + i * static_cast<double>(scan.angle_increment);
    const sim::RayHit hit =
        caster.Cast(Vec2(sensor.x, sensor.y), Vec2(std::cos(phi), std::sin(phi)), scan.max_range);
    if (hit.hit()) ++votes[hit.wall];
  }
  int best = -1, best_votes = 0;
  for (const auto& [w, v] : votes) {
    if (v > best_votes) {
      best = w;
      best_votes = v;
    }
  }
  if (best < 0) return false;
  line = LineThroughPoints(walls[best].a, walls[best].b);
  return true;
}

// The simulated base's calibration errors (wheel radii, track width) in the Monte Carlo.
enum class Calibration {
  kFixed,   // the simulator's defaults in every run (a 1-sigma error of the filter's model)
  kPerRun,  // drawn per run from N(0, sigma^2), sigma the defaults' sizes (the filter's model)
  kOff,     // none, and none modelled
};

std::string ApplyOverrides(const std::string& spec, LocalMapOptions& o);

// The Monte Carlo's simulated laser.
sim::LaserOptions McLaser() {
  sim::LaserOptions laser;
  laser.beams = 361;
  laser.range_sigma = kSimRangeSigma;
  laser.max_range = 30.0;
  return laser;
}

// The Monte Carlo's filter: it models the simulator's default calibration errors' sizes as
// standard deviations (none with Calibration::kOff).
LocalMapOptions McFilterOptions(int capacity, Calibration calibration) {
  WheelOdometryNoiseOptions modelled;
  if (calibration == Calibration::kOff) {
    modelled.left_scale_error = modelled.right_scale_error = modelled.track_width_error = 0.0;
  }
  return SimFilterOptions(capacity, modelled, McLaser());
}

// One run with the filter `options` (McFilterOptions, valid).
std::vector<StepNees> RunOnce(uint64_t seed, double minutes, const LocalMapOptions& options,
                              const std::vector<sim::Wall>& walls, const sim::RayCaster& caster,
                              Calibration calibration, int& features_out, OdometryCheck& check) {
  WheelOdometryNoiseOptions wheel;  // the simulator's defaults, calibration errors too
  const sim::LaserOptions laser = McLaser();
  if (calibration == Calibration::kPerRun) {
    std::mt19937_64 rng(seed * 6151 + 11);
    std::normal_distribution<double> unit(0.0, 1.0);
    wheel.left_scale_error = options.odometry.wheel_scale_sigma * unit(rng);
    wheel.right_scale_error = options.odometry.wheel_scale_sigma * unit(rng);
    wheel.track_width_error = options.odometry.track_width_sigma * unit(rng);
  } else if (calibration == Calibration::kOff) {
    wheel.left_scale_error = wheel.right_scale_error = wheel.track_width_error = 0.0;
  }
  LineEkfMap map(options);
  WheelOdometryModel odometry(wheel, seed * 7919 + 1);
  sim::LaserModel scanner(laser, seed * 104729 + 3);
  // Back and forth along the corridor centre, weaving a little.
  std::vector<Vec2> waypoints;
  for (int lap = 0; lap < 40; ++lap) {
    for (int i = 0; i <= 6; ++i) {
      const int k = lap % 2 == 0 ? i : 6 - i;
      waypoints.push_back(Vec2(1.0 + 3.0 * k, (k % 2 == 0 ? 0.25 : -0.25)));
    }
  }
  sim::MotionOptions motion;
  motion.max_speed = 0.6;
  sim::DiffDriveFollower follower(motion, waypoints);
  const double dt = 0.02;  // 50 Hz odometry
  const int steps = static_cast<int>(minutes * 60.0 / dt);
  const int scan_every = 5;  // 10 Hz laser
  std::vector<StepNees> out;
  out.reserve(steps / scan_every + 1);
  // The map-frame is the world frame: the robot starts at its first pose, known exactly.
  const Pose2 origin = follower.pose();
  Pose2 last_odo = odometry.Step(TruthSample{Time{}, origin}).pose;
  std::map<int, Vec2> true_line;  // feature id -> true line, map-frame
  // Dead reckoning from the last scan's true pose, with the filter's Predict (OdometryCheck).
  LineEkfMap interval(options);
  const UncertainPose zero_pose{Pose2{}, Mat3::Zero()};
  Pose2 last_truth = origin, scan_truth = origin;
  const double chi2_95 = ChiSquareQuantile(0.95, 3), chi2_99 = ChiSquareQuantile(0.99, 3);
  for (int s = 1; s <= steps; ++s) {
    follower.Step(dt);
    const Pose2 truth_world = follower.pose();
    const Pose2 odo = odometry.Step(TruthSample{FromSeconds(s * dt), truth_world}).pose;
    const Pose2 u = Between(last_odo, odo);
    map.Predict(u);
    interval.Predict(u);
    {
      const Pose2 u_true = Between(last_truth, truth_world);
      const Vec3 e(u.x - u_true.x, u.y - u_true.y, WrapAngle(u.theta - u_true.theta));
      const Eigen::SelfAdjointEigenSolver<Mat3> eig(LineEkfMap::OdometryNoise(u, options.odometry));
      if (eig.eigenvalues()(1) > 0.0) {
        // Signs fixed by the largest component, not by the solver (whose signs follow the noise).
        Eigen::Vector2d w;
        for (int i = 0; i < 2; ++i) {
          Vec3 v = eig.eigenvectors().col(i + 1);
          int big = 0;
          v.cwiseAbs().maxCoeff(&big);
          if (v(big) < 0.0) v = -v;
          w(i) = v.dot(e) / std::sqrt(eig.eigenvalues()(i + 1));
        }
        ++check.steps;
        check.step_sum += w;
        check.step_ww += w * w.transpose();
      }
    }
    last_odo = odo;
    last_truth = truth_world;
    if (s % scan_every != 0) continue;
    {
      const Pose2 rel = Between(scan_truth, truth_world);
      const UncertainPose est = interval.RobotPose();
      const Vec3 e(rel.x - est.mean.x, rel.y - est.mean.y, WrapAngle(rel.theta - est.mean.theta));
      const Eigen::LLT<Mat3> llt(est.cov);
      if (llt.info() == Eigen::Success) {
        const Vec3 w = llt.matrixL().solve(e);
        const double nees = w.squaredNorm();
        ++check.intervals;
        check.interval_nees += nees;
        check.interval_sum += w;
        check.interval_ww += w * w.transpose();
        check.interval_above95 += nees > chi2_95;
        check.interval_above99 += nees > chi2_99;
        if (s == scan_every) {
          ++check.firsts;
          check.first_above95 += nees > chi2_95;
          check.first_above99 += nees > chi2_99;
        }
      }
      interval.ResetRobotPose(zero_pose);
      scan_truth = truth_world;
    }
    const LaserScan scan = scanner.Scan(caster, truth_world, FromSeconds(s * dt));
    const ScanUpdate up = map.Update(scan, true);
    const Pose2 truth = Between(origin, truth_world);
    if (up.added > 0) {
      for (size_t j = 0; j < map.LastObservations().size(); ++j) {
        const int id = map.LastAssociation()[j];
        if (id < 0 || true_line.count(id)) continue;
        Vec2 line_world;
        if (!TrueLineOf(map.LastObservations()[j], truth_world, scan, caster, walls, line_world))
          continue;
        // World line -> map-frame line.
        LinePrediction p = PredictLine(origin, line_world(0), line_world(1));
        double rho = p.z(0), alpha = p.z(1);
        CanonicalizeLine(rho, alpha);
        true_line[id] = Vec2(rho, alpha);
        if (std::getenv("LOCALMAP_DEBUG")) {
          const ObservedLine zw = ObservedLineToParent(truth, map.LastObservations()[j]);
          std::fprintf(stderr,
                       "step %d add id %d obs (%.4f %.5f) true (%.4f %.5f) sd %.4f %.5f n %d beams "
                       "%d-%d len %.2f\n",
                       s, id, zw.rho, zw.alpha, rho, alpha, std::sqrt(zw.cov(0, 0)),
                       std::sqrt(zw.cov(1, 1)), zw.num_points, zw.first_beam, zw.last_beam,
                       zw.Length());
          const Pose2 sensor = Compose(truth_world, scan.sensor_pose);
          for (int i = zw.first_beam; i <= zw.last_beam; ++i) {
            const double phi =
                sensor.theta + scan.angle_min + i * static_cast<double>(scan.angle_increment);
            const sim::RayHit hit = caster.Cast(Vec2(sensor.x, sensor.y),
                                                Vec2(std::cos(phi), std::sin(phi)), scan.max_range);
            std::fprintf(stderr, " %d:%d", i, hit.wall);
          }
          std::fprintf(stderr, "\n");
        }
      }
    }
    StepNees n;
    const UncertainPose est = map.RobotPose();
    const Vec3 e(truth.x - est.mean.x, truth.y - est.mean.y,
                 WrapAngle(truth.theta - est.mean.theta));
    n.robot = e.dot(est.cov.ldlt().solve(e));
    std::vector<int> idx;
    std::vector<double> err;
    for (int k = 0; k < map.Complexity(); ++k) {
      auto it = true_line.find(map.FeatureId(k));
      if (it == true_line.end()) continue;
      double rho = map.State()(3 + 2 * k), alpha = map.State()(4 + 2 * k);
      CanonicalizeLine(rho, alpha);
      idx.push_back(3 + 2 * k);
      // Error in the state's own representation (flip sign of the rho error if flipped).
      const double sign = map.State()(3 + 2 * k) < 0.0 ? -1.0 : 1.0;
      err.push_back(sign * (it->second(0) - rho));
      err.push_back(WrapAngle(it->second(1) - alpha));
    }
    if (!idx.empty()) {
      const int d = 2 * static_cast<int>(idx.size());
      Eigen::MatrixXd pf(d, d);
      for (int a = 0; a < static_cast<int>(idx.size()); ++a) {
        for (int b = 0; b < static_cast<int>(idx.size()); ++b) {
          pf.block<2, 2>(2 * a, 2 * b) = map.Covariance().block<2, 2>(idx[a], idx[b]);
        }
      }
      const Eigen::VectorXd ef = Eigen::Map<Eigen::VectorXd>(err.data(), d);
      n.features = ef.dot(pf.ldlt().solve(ef));
      if (std::getenv("LOCALMAP_DEBUG") && s == steps - steps % scan_every) {
        for (int a = 0; a < static_cast<int>(idx.size()); ++a) {
          const Eigen::Vector2d ea = ef.segment<2>(2 * a);
          const Eigen::Matrix2d pa = pf.block<2, 2>(2 * a, 2 * a);
          std::fprintf(stderr, "feature %d (%.3f %.3f): err %.5f %.6f sd %.5f %.6f nees %.2f\n",
                       idx[a], map.State()(idx[a]), map.State()(idx[a] + 1), ea(0), ea(1),
                       std::sqrt(pa(0, 0)), std::sqrt(pa(1, 1)), ea.dot(pa.inverse() * ea));
        }
      }
      n.feature_dof = d;
    }
    out.push_back(n);
  }
  features_out = map.Complexity();
  return out;
}

std::vector<sim::Wall> SimCorridor() { return sim::CorridorWalls(20.0, 2.4); }

int RunMonteCarlo(const Args& args) {
  double minutes = 4;
  int runs = 50, seed = 1, capacity = 20, per_run = 0;
  std::string error;
  if (!GetIntegerOption(args, "--runs", 1, 10000, runs, error) ||
      !GetNumberOption(args, "--minutes", 0.05, 600, minutes, error) ||
      !GetIntegerOption(args, "--seed", 0, kMaxSeed, seed, error) ||
      !GetIntegerOption(args, "--capacity", 1, 1000, capacity, error) ||
      !GetIntegerOption(args, "--per-run", 0, 1, per_run, error)) {
    std::fprintf(stderr, "atlas-localmap-eval mc: %s\n", error.c_str());
    return 2;
  }
  Calibration calibration = Calibration::kFixed;
  if (auto it = args.values.find("--calibration"); it != args.values.end()) {
    if (it->second == "per-run") {
      calibration = Calibration::kPerRun;
    } else if (it->second == "off") {
      calibration = Calibration::kOff;
    } else if (it->second != "fixed") {
      std::fprintf(stderr,
                   "atlas-localmap-eval mc: --calibration must be fixed, per-run or off (got "
                   "'%s')\n",
                   it->second.c_str());
      return 2;
    }
  }
  std::string overrides;
  if (auto it = args.values.find("--set"); it != args.values.end()) overrides = it->second;
  LocalMapOptions filter = McFilterOptions(static_cast<int>(capacity), calibration);
  if (const std::string bad = ApplyOverrides(overrides, filter); !bad.empty()) {
    std::fprintf(stderr, "atlas-localmap-eval mc: %s\n", bad.c_str());
    return 2;
  }
  const std::vector<sim::Wall> walls = SimCorridor();
  const sim::RayCaster caster(walls);
  const int r_count = static_cast<int>(runs);
  std::vector<std::vector<StepNees>> all;
  double mean_features = 0.0;
  std::vector<std::pair<double, int>> run_mean;  // (mean robot NEES over the run, seed)
  OdometryCheck check;
  FILE* dump = nullptr;
  if (auto it = args.values.find("--dump"); it != args.values.end()) {
    dump = std::fopen(it->second.c_str(), "w");
    if (!dump) {
      std::fprintf(stderr, "atlas-localmap-eval mc: cannot write --dump file %s: %s\n",
                   it->second.c_str(), std::strerror(errno));
      return 2;
    }
  }
  if (per_run != 0) {
    std::printf(
        "per run: seed, robot NEES at the first scan, mean, max (scan), feature "
        "NEES/dof mean, at the last scan\n");
  }
  for (int r = 0; r < r_count; ++r) {
    int features = 0;
    all.push_back(RunOnce(static_cast<uint64_t>(seed) + r, minutes, filter, walls, caster,
                          calibration, features, check));
    mean_features += features;
    double run_nees = 0.0, run_max = 0.0, run_feat = 0.0;
    size_t max_at = 0;
    int feat_steps = 0;
    for (size_t k = 0; k < all.back().size(); ++k) {
      const StepNees& n = all.back()[k];
      run_nees += n.robot;
      if (n.robot > run_max) run_max = n.robot, max_at = k;
      if (n.feature_dof > 0) run_feat += n.features / n.feature_dof, ++feat_steps;
    }
    run_mean.push_back(
        {run_nees / std::max<size_t>(1, all.back().size()), static_cast<int>(seed) + r});
    if (dump) {
      std::fprintf(dump, "robot %d", static_cast<int>(seed) + r);
      for (const StepNees& n : all.back()) std::fprintf(dump, " %.4g", n.robot);
      std::fprintf(dump, "\nfeatures %d", static_cast<int>(seed) + r);
      for (const StepNees& n : all.back())
        std::fprintf(dump, " %.4g:%d", n.features, n.feature_dof);
      std::fprintf(dump, "\n");
    }
    if (per_run != 0 && !all.back().empty()) {
      const StepNees& last = all.back().back();
      std::printf("run %d: %.3f %.3f %.3f (%zu) %.3f %.3f\n", static_cast<int>(seed) + r,
                  all.back()[0].robot, run_mean.back().first, run_max, max_at,
                  run_feat / std::max(1, feat_steps),
                  last.feature_dof > 0 ? last.features / last.feature_dof : 0.0);
    }
    std::fprintf(stderr, "\rrun %d/%d done (%zu steps, %d features)   ", r + 1, r_count,
                 all.back().size(), features);
  }
  std::fprintf(stderr, "\n");
  if (dump) std::fclose(dump);
  size_t steps = all[0].size();
  for (const auto& a : all) steps = std::min(steps, a.size());
  const double lo = ChiSquareQuantile(0.025, 3 * r_count) / r_count;
  const double hi = ChiSquareQuantile(0.975, 3 * r_count) / r_count;
  int robot_in = 0, feat_in = 0, feat_steps = 0;
  double robot_mean = 0.0, feat_mean = 0.0;
  std::vector<double> robot_avg(steps), feat_avg(steps, -1.0);
  for (size_t k = 0; k < steps; ++k) {
    double sum = 0.0, fsum = 0.0;
    int dof = 0;
    for (const auto& a : all) {
      sum += a[k].robot;
      fsum += a[k].features;
      dof += a[k].feature_dof;
    }
    robot_avg[k] = sum / r_count;
    robot_mean += robot_avg[k];
    if (robot_avg[k] >= lo && robot_avg[k] <= hi) ++robot_in;
    if (dof > 0) {
      const double f = fsum / dof;  // average NEES per degree of freedom
      feat_avg[k] = f;
      feat_mean += f;
      ++feat_steps;
      if (f >= ChiSquareQuantile(0.025, dof) / dof && f <= ChiSquareQuantile(0.975, dof) / dof)
        ++feat_in;
    }
  }
  std::printf(
      "Monte Carlo: %d runs x %.1f min (%zu scan steps each, 10 Hz laser, 50 Hz odometry),"
      " corridor 20 m, capacity %d, mean final features %.1f\n",
      r_count, minutes, steps, static_cast<int>(capacity), mean_features / r_count);
  std::printf("laser range sigma: simulator %.4f m, filter %.4f m%s\n", kSimRangeSigma,
              filter.extraction.range_sigma, overrides.empty() ? "" : " (--set)");
  std::printf(
      "robot NEES (3 dof), average over %d runs: 95%% band [%.3f, %.3f]; mean %.3f; "
      "steps inside %d/%zu = %.1f%%\n",
      r_count, lo, hi, robot_mean / steps, robot_in, steps, 100.0 * robot_in / steps);
  const int fd = all[0].back().feature_dof;
  const double flo = fd > 0 ? ChiSquareQuantile(0.025, fd * r_count) / (fd * r_count) : 0.0;
  const double fhi = fd > 0 ? ChiSquareQuantile(0.975, fd * r_count) / (fd * r_count) : 0.0;
  std::printf(
      "feature NEES per dof (joint over all features, summed over runs): band at the "
      "last step [%.3f, %.3f] (%d dof per run); mean %.3f; steps inside %d/%d = %.1f%%\n",
      flo, fhi, fd, feat_steps ? feat_mean / feat_steps : 0.0, feat_in, feat_steps,
      feat_steps ? 100.0 * feat_in / feat_steps : 0.0);
  if (check.steps > 0 && check.intervals > 0) {
    const Eigen::Vector2d sm = check.step_sum / check.steps;
    const Eigen::Matrix2d sc = check.step_ww / check.steps - sm * sm.transpose();
    const Eigen::Vector3d im = check.interval_sum / check.intervals;
    const Eigen::Matrix3d ic = check.interval_ww / check.intervals - im * im.transpose();
    std::printf(
        "odometry vs the filter's Q: %ld steps whitened: mean (%.3f %.3f), covariance "
        "[%.3f %.3f; %.3f %.3f] (I if Q is right); %ld scan intervals: NEES mean %.3f (3), "
        "whitened mean (%.3f %.3f %.3f), covariance diagonal (%.3f %.3f %.3f)\n",
        check.steps, sm(0), sm(1), sc(0, 0), sc(0, 1), sc(1, 0), sc(1, 1), check.intervals,
        check.interval_nees / check.intervals, im(0), im(1), im(2), ic(0, 0), ic(1, 1), ic(2, 2));
    std::printf(
        "  interval NEES above the 95%% / 99%% points: %.2f%% / %.2f%% (first interval of each "
        "run: %.2f%% / %.2f%% of %ld)\n",
        100.0 * check.interval_above95 / check.intervals,
        100.0 * check.interval_above99 / check.intervals,
        100.0 * check.first_above95 / std::max(1L, check.firsts),
        100.0 * check.first_above99 / std::max(1L, check.firsts), check.firsts);
  }
  // Errors that enter the unobservable directions (the map-frame's heading and position, fixed
  // by the first scans) stay for the whole run: a few runs set the average of every step.
  // How much of each run's mean is set at its first scan (before any feature fixes the frame).
  {
    double sf = 0.0, sm = 0.0, sff = 0.0, smm = 0.0, sfm = 0.0;
    for (int r = 0; r < r_count; ++r) {
      const double f = all[r].empty() ? 0.0 : all[r][0].robot, m = run_mean[r].first;
      sf += f, sm += m, sff += f * f, smm += m * m, sfm += f * m;
    }
    const double cov = sfm / r_count - sf * sm / (r_count * r_count);
    const double vf = sff / r_count - sf * sf / (r_count * r_count);
    const double vm = smm / r_count - sm * sm / (r_count * r_count);
    std::printf(
        "robot NEES at the first scan: mean over runs %.3f, above the 99%% point in %d of %d "
        "runs; correlation with the run's mean NEES %.2f\n",
        sf / r_count,
        static_cast<int>(std::count_if(all.begin(), all.end(),
                                       [](const std::vector<StepNees>& a) {
                                         return !a.empty() &&
                                                a[0].robot > ChiSquareQuantile(0.99, 3);
                                       })),
        r_count, vf > 0.0 && vm > 0.0 ? cov / std::sqrt(vf * vm) : 0.0);
  }
  std::sort(run_mean.rbegin(), run_mean.rend());
  std::printf("runs with the largest mean robot NEES (seed: mean):");
  for (size_t i = 0; i < std::min<size_t>(5, run_mean.size()); ++i) {
    std::printf(" %d: %.2f", run_mean[i].second, run_mean[i].first);
  }
  std::printf("\n");
  // A coarse profile over time.
  std::printf("time profile (step: robot NEES avg, feature NEES/dof avg):\n");
  for (size_t k = 0; k < steps; k += std::max<size_t>(1, steps / 12)) {
    std::printf("  %5zu  %.3f  %.3f\n", k, robot_avg[k], feat_avg[k]);
  }
  return 0;
}

// ---------------------------------------------------------------------------------------------
// Real data.

LocalMapOptions RealFilterOptions(int capacity) {
  LocalMapOptions o;
  o.capacity = capacity;
  o.extraction.range_sigma = 0.01;
  // Walls that are not straight to the centimetre plus the log's 1 cm range quantisation: at
  // 0.015 the chi-square fit test (extraction.fit_gate) rejected 6 % of the lines.
  o.extraction.model_sigma = 0.03;
  o.extraction.split_distance = 0.06;
  o.extraction.min_points = 10;
  o.extraction.min_length = 0.6;
  o.odometry.track_width = 0.5;
  o.odometry.wheel_var_per_m = 1e-4;
  o.odometry.xy_var_per_m = 1e-3;
  o.odometry.xy_var_per_rad = 1e-4;
  o.odometry.theta_var_per_m = 5e-3;
  o.odometry.theta_var_per_rad = 3e-2;
  o.extraction.min_rho_sigma = 0.03;
  o.extraction.min_alpha_sigma = 0.02;
  o.association.new_feature_min_length = 1.0;
  return o;
}

// --set name=value,name=value: overrides of the filter options (see the table).
std::string ApplyOverrides(const std::string& spec, LocalMapOptions& o) {
  const std::map<std::string, double*> table = {
      {"range_sigma", &o.extraction.range_sigma},
      {"model_sigma", &o.extraction.model_sigma},
      {"min_rho_sigma", &o.extraction.min_rho_sigma},
      {"min_alpha_sigma", &o.extraction.min_alpha_sigma},
      {"split_distance", &o.extraction.split_distance},
      {"min_length", &o.extraction.min_length},
      {"max_gap", &o.extraction.max_gap},
      {"fit_gate", &o.extraction.fit_gate},
      {"duplicate_rho", &o.association.duplicate_rho},
      {"duplicate_alpha", &o.association.duplicate_alpha},
      {"wheel_scale_sigma", &o.odometry.wheel_scale_sigma},
      {"wheel_var_per_m", &o.odometry.wheel_var_per_m},
      {"xy_var_per_m", &o.odometry.xy_var_per_m},
      {"xy_var_per_rad", &o.odometry.xy_var_per_rad},
      {"theta_var_per_m", &o.odometry.theta_var_per_m},
      {"theta_var_per_rad", &o.odometry.theta_var_per_rad},
      {"individual_gate", &o.association.individual_gate},
      {"joint_gate", &o.association.joint_gate},
      {"max_extent_gap", &o.association.max_extent_gap},
      {"ambiguity_margin", &o.association.ambiguity_margin},
      {"new_feature_min_length", &o.association.new_feature_min_length},
      {"new_feature_gate", &o.association.new_feature_gate},
      {"recovery_gate", &o.association.recovery_gate},
  };
  const std::map<std::string, int*> int_table = {
      {"min_points", &o.extraction.min_points},
      {"corner_points", &o.extraction.corner_points},
  };
  size_t pos = 0;
  while (pos < spec.size()) {
    size_t end = spec.find(',', pos);
    if (end == std::string::npos) end = spec.size();
    const std::string item = spec.substr(pos, end - pos);
    const size_t eq = item.find('=');
    double v = 0.0;
    const std::string name = eq == std::string::npos ? item : item.substr(0, eq);
    const bool is_int = int_table.count(name) > 0;
    if (eq == std::string::npos || (!table.count(name) && !is_int) ||
        !ParseNumber(item.substr(eq + 1).c_str(), &v) ||
        (is_int && (v != std::floor(v) || std::abs(v) > 1e6))) {
      std::string names;
      for (const auto& [n, p] : table) names += " " + n;
      for (const auto& [n, p] : int_table) names += " " + n + " (integer)";
      return "--set: bad item '" + item + "' (want name=number; names:" + names + ")";
    }
    if (is_int) {
      *int_table.at(name) = static_cast<int>(v);
    } else {
      *table.at(name) = v;
    }
    pos = end + 1;
  }
  return o.Validate();
}

struct ScanRecord {
  Time stamp{};
  int stretch = 0;
  Pose2 estimate;        // in the stretch's map-frame
  Pose2 odometry;        // the log's, at the stamp
  Pose2 odometry_taken;  // at the stamp + laser time offset (the filter's)
  const LaserScan* scan = nullptr;
};

int RunReal(const Args& args) {
  std::string log_path = std::string(ATLAS_SHARED_DIR) + "/datasets/mit-csail/mit-csail.clf.gz";
  std::string rel_path = std::string(ATLAS_SHARED_DIR) + "/datasets/mit-csail/mit-csail.relations";
  if (args.values.count("--log")) log_path = args.values.at("--log");
  if (args.values.count("--relations")) rel_path = args.values.at("--relations");
  double stretch_m = 30, draw_stretch = 3, laser_x = 0.0, time_offset_s = 0.0;
  int capacity = 100, scan_match = 1;
  std::string error;
  if (!GetNumberOption(args, "--stretch", 1, 1e6, stretch_m, error) ||
      !GetNumberOption(args, "--laser-x", -2, 2, laser_x, error) ||
      !GetNumberOption(args, "--laser-time-offset", -1, 1, time_offset_s, error) ||
      !GetIntegerOption(args, "--scan-match", 0, 1, scan_match, error) ||
      !GetIntegerOption(args, "--capacity", 1, 10000, capacity, error) ||
      !GetNumberOption(args, "--draw-stretch", 0, 1e6, draw_stretch, error)) {
    std::fprintf(stderr, "atlas-localmap-eval real: %s\n", error.c_str());
    return 2;
  }
  std::fprintf(stderr, "reading %s ...\n", log_path.c_str());
  const carmen::CarmenReadResult read = carmen::ReadCarmenLog(log_path, carmen::CarmenLogOptions());
  if (!read.ok()) {
    std::fprintf(stderr, "atlas-localmap-eval real: cannot read the log: %s (give --log FILE)\n",
                 read.error.c_str());
    return 1;
  }
  const eval::TextFile rel_text = eval::ReadTextFile(rel_path);
  if (!rel_text.error.empty()) {
    std::fprintf(stderr, "atlas-localmap-eval real: %s (give --relations FILE)\n",
                 rel_text.error.c_str());
    return 1;
  }
  const eval::RelationsParse rels = eval::ParseRelations(rel_text.text, rel_path);
  if (!rels.error.empty()) {
    std::fprintf(stderr, "atlas-localmap-eval real: %s\n", rels.error.c_str());
    return 1;
  }
  LocalMapOptions options = RealFilterOptions(static_cast<int>(capacity));
  const std::string invalid =
      ApplyOverrides(args.values.count("--set") ? args.values.at("--set") : "", options);
  if (!invalid.empty()) {
    std::fprintf(stderr, "atlas-localmap-eval real: bad filter options: %s\n", invalid.c_str());
    return 1;
  }
  // The odometry of the laser lines, to look it up at stamp + offset (as atlasd's loop does).
  std::vector<OdometrySample> samples;
  for (const carmen::CarmenEvent& ev : read.log.events) {
    const LaserScan* scan = std::get_if<LaserScan>(&ev.event);
    if (scan != nullptr && ev.odometry_pose) samples.push_back({scan->stamp, *ev.odometry_pose});
  }
  OdometryTrack track(samples.size(), Duration::zero());
  for (const OdometrySample& o : samples) track.Add(o);
  const Duration time_offset = FromSeconds(time_offset_s).time_since_epoch();
  std::vector<ScanRecord> records;
  std::unique_ptr<LineEkfMap> map;
  std::unique_ptr<LineEkfMap> drawn;
  std::vector<size_t> drawn_records;
  int stretch = -1;
  double travelled = 0.0;
  Pose2 last_odo;
  bool have_odo = false;
  int updates = 0, matched = 0, observed = 0, ambiguous = 0, recovered = 0;
  ScanMatchOptions match_options;
  match_options.enabled = scan_match != 0;
  ScanMatcher matcher(match_options);
  int64_t increments_matched = 0, match_fallbacks = 0;
  for (const carmen::CarmenEvent& ev : read.log.events) {
    const LaserScan* scan = std::get_if<LaserScan>(&ev.event);
    if (scan == nullptr || !ev.odometry_pose) continue;
    Pose2 odo = *ev.odometry_pose;
    if (time_offset != Duration::zero()) track.PoseAt(scan->stamp + time_offset, &odo);
    Pose2 delta;
    if (have_odo) {
      delta = Between(last_odo, odo);
      travelled += std::hypot(delta.x, delta.y);
    }
    LaserScan mounted = *scan;
    mounted.sensor_pose = Compose(Pose2{laser_x, 0.0, 0.0}, scan->sensor_pose);
    if (!map || travelled >= stretch_m) {
      if (map && stretch == static_cast<int>(draw_stretch)) drawn = std::move(map);
      map = std::make_unique<LineEkfMap>(options);
      ++stretch;
      travelled = 0.0;
    } else if (match_options.enabled && matcher.HasReference()) {
      const ScanMatchResult m =
          matcher.Match(mounted, {delta, LineEkfMap::OdometryNoise(delta, options.odometry)});
      if (m.outcome == ScanMatchOutcome::kMatched) {
        ++increments_matched;
        map->Predict(m.increment.mean, m.increment.cov);
      } else {
        ++match_fallbacks;
        map->Predict(delta);
      }
    } else {
      map->Predict(delta);
    }
    if (match_options.enabled) matcher.SetReference(mounted);
    last_odo = odo;
    have_odo = true;
    const UncertainPose prior = map->RobotPose();
    const ScanUpdate up = map->Update(mounted, true);
    if (std::getenv("LOCALMAP_DEBUG") && up.added > 0) {
      const UncertainPose rp = map->RobotPose();
      for (const MapLine& l : map->Lines()) {
        if (l.id < map->Lines().back().id - up.added + 1) continue;
        std::fprintf(stderr,
                     "scan t %.2f stretch %d: new feature %d (%.3f m, %.2f deg) length %.2f m, "
                     "robot sd %.3f m %.1f deg, %d features\n",
                     ToSeconds(scan->stamp.time_since_epoch()), stretch, l.id, l.rho,
                     l.alpha * 180 / M_PI, (l.endpoint_b - l.endpoint_a).norm(),
                     std::sqrt(rp.cov(0, 0) + rp.cov(1, 1)), std::sqrt(rp.cov(2, 2)) * 180 / M_PI,
                     map->Complexity());
      }
    }
    if (std::getenv("LOCALMAP_DEBUG")) {
      const double turn = WrapAngle(map->RobotPose().mean.theta - prior.mean.theta);
      if (std::abs(turn) > 0.05) {
        std::fprintf(
            stderr,
            "scan t %.2f stretch %d: heading corrected %.1f deg (prior sd %.1f deg, odometry "
            "step %.1f deg), %d lines, %d matched%s, %d features\n",
            ToSeconds(scan->stamp.time_since_epoch()), stretch, turn * 180 / M_PI,
            std::sqrt(prior.cov(2, 2)) * 180 / M_PI, delta.theta * 180 / M_PI, up.observations,
            up.matched, map->LastUpdateRecovered() ? " (recovery)" : "", map->Complexity());
      }
    }
    ++updates;
    recovered += map->LastUpdateRecovered() ? 1 : 0;
    matched += up.matched;
    observed += up.observations;
    ambiguous += up.ambiguous ? 1 : 0;
    records.push_back(
        ScanRecord{scan->stamp, stretch, map->RobotPose().mean, *ev.odometry_pose, odo, scan});
    if (stretch == static_cast<int>(draw_stretch)) drawn_records.push_back(records.size() - 1);
  }
  if (map && stretch == static_cast<int>(draw_stretch)) drawn = std::move(map);
  std::fprintf(stderr,
               "%d scans, %d stretches of %.0f m; %d lines observed, %d matched (%.1f%%), "
               "%d scans with an ambiguous association, %d paired only by the recovery pass\n",
               updates, stretch + 1, stretch_m, observed, matched,
               100.0 * matched / std::max(1, observed), ambiguous, recovered);
  if (match_options.enabled) {
    std::fprintf(stderr, "scan matching: %lld increments matched, %lld fell back to the odometry\n",
                 static_cast<long long>(increments_matched),
                 static_cast<long long>(match_fallbacks));
  }

  // Relations with both poses in one stretch.
  auto find = [&](Time t) -> const ScanRecord* {
    auto it = std::lower_bound(records.begin(), records.end(), t,
                               [](const ScanRecord& r, Time x) { return r.stamp < x; });
    const ScanRecord* best = nullptr;
    Duration best_d = eval::kDefaultMatchTolerance + Duration(1);
    for (auto c : {it, it == records.begin() ? it : it - 1}) {
      if (c == records.end()) continue;
      const Duration d = c->stamp > t ? c->stamp - t : t - c->stamp;
      if (d < best_d) {
        best_d = d;
        best = &*c;
      }
    }
    return best_d <= eval::kDefaultMatchTolerance ? best : nullptr;
  };
  std::vector<double> est_t, est_r, dr_t, dr_r, drs_t, drs_r;
  int unmatched = 0, cross_stretch = 0;
  for (const eval::Relation& rel : rels.relations) {
    const ScanRecord* a = find(rel.t1);
    const ScanRecord* b = find(rel.t2);
    if (a == nullptr || b == nullptr) {
      ++unmatched;
      continue;
    }
    if (a->stretch != b->stretch) {
      ++cross_stretch;
      continue;
    }
    const eval::RelationError e = eval::RelationErrorOf(rel, Between(a->estimate, b->estimate));
    const eval::RelationError d = eval::RelationErrorOf(rel, Between(a->odometry, b->odometry));
    if (std::getenv("LOCALMAP_DEBUG")) {
      std::fprintf(stderr,
                   "rel stretch %d t %.2f dt %.2f move %.3f %.3f: ekf %.4f %.3f dr %.4f %.3f "
                   "(odometry turn %.3f, ekf turn %.3f)\n",
                   a->stretch, ToSeconds(rel.t1.time_since_epoch()), ToSeconds(rel.t2 - rel.t1),
                   rel.delta.x, rel.delta.theta, e.translation_m, e.rotation_deg, d.translation_m,
                   d.rotation_deg, Between(a->odometry, b->odometry).theta,
                   Between(a->estimate, b->estimate).theta);
    }
    est_t.push_back(e.translation_m);
    est_r.push_back(e.rotation_deg);
    dr_t.push_back(d.translation_m);
    dr_r.push_back(d.rotation_deg);
    const eval::RelationError ds =
        eval::RelationErrorOf(rel, Between(a->odometry_taken, b->odometry_taken));
    drs_t.push_back(ds.translation_m);
    drs_r.push_back(ds.rotation_deg);
  }
  const eval::ErrorStats et = eval::Summarize(est_t), er = eval::Summarize(est_r);
  const eval::ErrorStats dt = eval::Summarize(dr_t), dr = eval::Summarize(dr_r);
  const eval::ErrorStats dst = eval::Summarize(drs_t), dsr = eval::Summarize(drs_r);
  std::printf(
      "mit-csail: %zu relations; scored %zu (both poses in one %.0f m stretch), %d across "
      "stretches, %d without a scan\n",
      rels.relations.size(), est_t.size(), stretch_m, cross_stretch, unmatched);
  std::printf(
      "  local map EKF  : trans %.4f +- %.4f m (rmse %.4f, max %.3f), rot %.3f +- %.3f deg\n",
      et.mean, et.stddev, et.rmse, et.max, er.mean, er.stddev);
  std::printf(
      "  dead reckoning : trans %.4f +- %.4f m (rmse %.4f, max %.3f), rot %.3f +- %.3f deg\n",
      dt.mean, dt.stddev, dt.rmse, dt.max, dr.mean, dr.stddev);
  if (time_offset != Duration::zero()) {
    std::printf(
        "  dead reckoning at stamp %+.3f s: trans %.4f +- %.4f m (rmse %.4f, max %.3f), rot %.3f "
        "+- %.3f deg\n",
        time_offset_s, dst.mean, dst.stddev, dst.rmse, dst.max, dsr.mean, dsr.stddev);
  }
  auto median = [](std::vector<double> v) {
    if (v.empty()) return 0.0;
    std::nth_element(v.begin(), v.begin() + v.size() / 2, v.end());
    return v[v.size() / 2];
  };
  std::printf(
      "  medians: EKF trans %.4f m rot %.3f deg; dead reckoning trans %.4f m rot %.3f deg\n",
      median(est_t), median(est_r), median(dr_t), median(dr_r));
  std::printf("  ratio dead reckoning / EKF: translation %.2f, rotation %.2f (target >= 5)\n",
              dt.mean / std::max(et.mean, 1e-12), dr.mean / std::max(er.mean, 1e-12));
  if (time_offset != Duration::zero()) {
    std::printf("  ratio dead reckoning at stamp %+.3f s / EKF: translation %.2f, rotation %.2f\n",
                time_offset_s, dst.mean / std::max(et.mean, 1e-12),
                dsr.mean / std::max(er.mean, 1e-12));
  }

  if (args.values.count("--png") && drawn && !drawn_records.empty()) {
    const std::string png = args.values.at("--png");
    std::vector<Vec2> points;
    std::vector<Vec2> path;
    Vec2 lo(1e9, 1e9), hi(-1e9, -1e9);
    for (size_t i : drawn_records) {
      const ScanRecord& r = records[i];
      const Pose2 sensor =
          Compose(r.estimate, Compose(Pose2{laser_x, 0.0, 0.0}, r.scan->sensor_pose));
      path.push_back(Vec2(r.estimate.x, r.estimate.y));
      for (size_t b = 0; b < r.scan->ranges.size(); ++b) {
        const float range = r.scan->ranges[b];
        if (!IsReturn(range) || range > 15.0f) continue;
        const double phi = r.scan->angle_min + b * static_cast<double>(r.scan->angle_increment);
        const Vec2 p = sensor.TransformPoint(Vec2(range * std::cos(phi), range * std::sin(phi)));
        points.push_back(p);
        lo = lo.cwiseMin(p);
        hi = hi.cwiseMax(p);
      }
    }
    std::string err;
    draw::ImageFormat format;
    if (!draw::ImageFormatOf(png, &format)) {
      std::fprintf(stderr, "atlas-localmap-eval: --png must end in .png or .svg\n");
      return 1;
    }
    const draw::ViewTransform view =
        draw::ViewTransform::Fit(lo - Vec2(1, 1), hi + Vec2(1, 1), 10, 40, 1580, 1150);
    auto canvas = draw::Canvas::Create(format, png, 1600, 1200, view, &err);
    if (!canvas) {
      std::fprintf(stderr, "atlas-localmap-eval: %s\n", err.c_str());
      return 1;
    }
    canvas->Points(points, draw::Color{0.55, 0.55, 0.55, 0.35}, 0.7);
    canvas->Polyline(path, draw::Stroke{draw::Color{0.1, 0.4, 0.9, 1.0}, 2.0, false});
    for (const MapLine& l : drawn->Lines()) {
      canvas->Line(l.endpoint_a, l.endpoint_b,
                   draw::Stroke{draw::Color{0.85, 0.1, 0.1, 1.0}, 3.0, false});
      canvas->CovarianceEllipse(
          0.5 * (l.endpoint_a + l.endpoint_b),
          Eigen::Matrix2d(Eigen::Vector2d(l.cov(0, 0), l.cov(0, 0)).asDiagonal()), 3.0,
          draw::Stroke{draw::Color{0.85, 0.1, 0.1, 0.6}, 1.0, false});
    }
    const UncertainPose rp = drawn->RobotPose();
    canvas->Pose(rp.mean, 0.25, draw::Color{0.1, 0.4, 0.9, 1.0});
    canvas->CovarianceEllipse(Vec2(rp.mean.x, rp.mean.y), rp.cov.topLeftCorner<2, 2>(), 3.0,
                              draw::Stroke{draw::Color{0.1, 0.4, 0.9, 1.0}, 1.5, false});
    char title[200];
    std::snprintf(title, sizeof(title),
                  "mit-csail stretch %d: %zu scans, %d lines (EKF, map-frame of the stretch)",
                  static_cast<int>(draw_stretch), drawn_records.size(), drawn->Complexity());
    canvas->TextPx(Vec2(12, 28), title, 20, draw::Color{}, true);
    canvas->ScaleBar();
    canvas->Legend(Vec2(12, 1185), {{"scan points (estimated poses)", {0.55, 0.55, 0.55, 1}, true},
                                    {"map lines (extent)", {0.85, 0.1, 0.1, 1}, false},
                                    {"robot path, 3-sigma pose", {0.1, 0.4, 0.9, 1}, false}});
    const std::string fin = canvas->Finish();
    if (!fin.empty()) {
      std::fprintf(stderr, "atlas-localmap-eval: %s\n", fin.c_str());
      return 1;
    }
    std::printf("wrote %s (stretch %d)\n", png.c_str(), static_cast<int>(draw_stretch));
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
    const atlas::Args a =
        atlas::eval::ParseToolOptions(argc, argv, 2,
                                      {"--runs", "--minutes", "--seed", "--capacity", "--per-run",
                                       "--dump", "--calibration", "--set"});
    if (!a.error.empty()) {
      std::fprintf(stderr, "atlas-localmap-eval mc: %s\n%s", a.error.c_str(), atlas::kUsage);
      return 2;
    }
    return atlas::RunMonteCarlo(a);
  }
  if (cmd == "real") {
    const atlas::Args a = atlas::eval::ParseToolOptions(
        argc, argv, 2,
        {"--log", "--relations", "--stretch", "--capacity", "--png", "--draw-stretch", "--set",
         "--laser-x", "--laser-time-offset", "--scan-match"});
    if (!a.error.empty()) {
      std::fprintf(stderr, "atlas-localmap-eval real: %s\n%s", a.error.c_str(), atlas::kUsage);
      return 2;
    }
    return atlas::RunReal(a);
  }
  std::fprintf(stderr, "atlas-localmap-eval: unknown command '%s'\n%s", cmd.c_str(), atlas::kUsage);
  return 2;
}
