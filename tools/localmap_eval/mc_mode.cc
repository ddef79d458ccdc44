#include "tools/localmap_eval/mc_mode.h"

#include <Eigen/Cholesky>
#include <Eigen/Eigenvalues>
#include <algorithm>
#include <cerrno>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <map>
#include <random>
#include <string>
#include <utility>
#include <vector>

#include "core/localmap/jcbb.h"
#include "core/localmap/line_ekf_map.h"
#include "core/localmap/line_model.h"
#include "sim/laser_model.h"
#include "sim/ray_caster.h"
#include "sim/route.h"
#include "sim/wheel_odometry_model.h"
#include "tools/cli/command_line.h"
#include "tools/localmap_eval/filter_overrides.h"
#include "tools/monte_carlo/corridor.h"
#include "tools/monte_carlo/nees_band.h"
#include "tools/monte_carlo/simulated_base.h"

namespace atlas::localmap_eval {
namespace {

using cli::GetIntegerOption;
using cli::GetNumberOption;

// Seeds S..S+runs-1 are printed as int.
constexpr int kMaxSeed = 1000000000;

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
// jambs: the split's noise-dependent corner) that repeat in every
// scan and add up over the thousands of fits fused into one feature. Five per cent more range
// noise covers them: over seeds 1-1000 the robot NEES averages 2.99 (3 dof) and the feature
// NEES 0.98 per dof, against 3.16 and 1.07 with the exact sigma.
constexpr double kRangeSigmaMargin = 1.05;
constexpr double kSimRangeSigma = 0.01;  // the simulated laser's, metres

LocalMapOptions SimFilterOptions(int capacity, const WheelOdometryNoiseOptions& wheel,
                                 const sim::LaserOptions& laser) {
  LocalMapOptions o;
  o.capacity = capacity;
  mc::UseSimulatedWalls(laser.range_sigma * kRangeSigmaMargin, &o.extraction);
  o.odometry = mc::SimulatedBaseOdometry(wheel);
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
  WheelOdometryModel odometry(wheel, mc::OdometrySeed(seed));
  sim::LaserModel scanner(laser, mc::LaserSeed(seed));
  sim::DiffDriveFollower follower(mc::CorridorMotion(), mc::CorridorWaypoints());
  const double dt = mc::kOdometryDt;
  const int steps = static_cast<int>(minutes * 60.0 / dt);
  const int scan_every = mc::kScanEvery;
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

// The options' defaults.
struct McDefaults {
  int runs = 50;
  double minutes = 4;
  int seed = 1;
  int capacity = 20;
  int per_run = 0;
};

int RunMcMode(const cli::ToolOptions& args) {
  const McDefaults d;
  double minutes = d.minutes;
  int runs = d.runs, seed = d.seed, capacity = d.capacity, per_run = d.per_run;
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
  const std::vector<sim::Wall> walls = mc::CorridorWalls();
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
  std::vector<std::vector<double>> robot_nees(all.size());
  for (size_t r = 0; r < all.size(); ++r)
    for (const StepNees& n : all[r]) robot_nees[r].push_back(n.robot);
  const mc::StepMeans robot_avg = mc::MeanPerStep(robot_nees);
  const mc::NeesBand band = mc::MeanNeesBand(3, r_count);
  const mc::BandSummary robot = mc::SummarizeInBand(robot_avg, band);
  int feat_in = 0, feat_steps = 0;
  double feat_mean = 0.0;
  std::vector<double> feat_avg(steps, -1.0);
  for (size_t k = 0; k < steps; ++k) {
    double fsum = 0.0;
    int dof = 0;
    for (const auto& a : all) {
      fsum += a[k].features;
      dof += a[k].feature_dof;
    }
    if (dof > 0) {
      const double f = fsum / dof;  // average NEES per degree of freedom
      feat_avg[k] = f;
      feat_mean += f;
      ++feat_steps;
      const mc::NeesBand per_dof = mc::MeanNeesBand(1, dof);
      if (f >= per_dof.lo && f <= per_dof.hi) ++feat_in;
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
      r_count, band.lo, band.hi, robot.mean, robot.inside, steps, robot.InsidePercent());
  const int fd = all[0].back().feature_dof;
  const mc::NeesBand feature_band = fd > 0 ? mc::MeanNeesBand(1, fd * r_count) : mc::NeesBand{};
  std::printf(
      "feature NEES per dof (joint over all features, summed over runs): band at the "
      "last step [%.3f, %.3f] (%d dof per run); mean %.3f; steps inside %d/%d = %.1f%%\n",
      feature_band.lo, feature_band.hi, fd, feat_steps ? feat_mean / feat_steps : 0.0, feat_in,
      feat_steps, feat_steps ? 100.0 * feat_in / feat_steps : 0.0);
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
    std::printf("  %5zu  %.3f  %.3f\n", k, robot_avg.mean[k], feat_avg[k]);
  }
  return 0;
}

}  // namespace

cli::ToolMode McMode() {
  const McDefaults d;
  return {
      "mc",
      "Monte Carlo consistency of the line EKF in a simulated corridor",
      {{"--runs", "N", "runs, noise seeds S..S+N-1 (default " + std::to_string(d.runs) + ")"},
       {"--minutes", "M", "minutes driven per run (default " + cli::HelpNumber(d.minutes) + ")"},
       {"--seed", "S", "the first run's noise seed (default " + std::to_string(d.seed) + ")"},
       {"--capacity", "C", "map capacity (default " + std::to_string(d.capacity) + ")"},
       {"--per-run", "0|1",
        "1: each run's NEES at the first scan, mean and max (default " + std::to_string(d.per_run) +
            ")"},
       {"--dump", "F", "every run's per-scan NEES to F (default: none)"},
       {"--calibration", "fixed|per-run|off", "the base's calibration errors (default fixed)"},
       {"--set", "name=v,...", "filter options overridden, as in real (default: none)"}},
      RunMcMode};
}

}  // namespace atlas::localmap_eval
