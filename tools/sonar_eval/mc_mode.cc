#include "tools/sonar_eval/mc_mode.h"

#include <Eigen/Cholesky>
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <numbers>
#include <string>
#include <utility>
#include <vector>

#include "core/eval/error_stats.h"
#include "core/localmap/jcbb.h"
#include "core/localmap/line_model.h"
#include "core/sonar/sonar_local_map.h"
#include "tools/cli/command_line.h"
#include "tools/monte_carlo/corridor.h"
#include "tools/monte_carlo/nees_band.h"
#include "tools/sonar_eval/corridor_run.h"
#include "tools/sonar_eval/sonar_atlas_run.h"

namespace atlas::sonar_eval {
namespace {

using cli::GetIntegerOption;
using cli::GetNumberOption;

// The options' defaults.
struct McDefaults {
  int runs = 20;
  double minutes = 3;
  int ring = 24;
  int seed = 1;
  int capacity = 20;
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
  for (const Vec2& w : WallLinesInFrame(walls, origin)) {
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
  c.topLeftCorner<3, 3>() +=
      Vec3(kNeesFloorM * kNeesFloorM, kNeesFloorM * kNeesFloorM, kNeesFloorRad * kNeesFloorRad)
          .asDiagonal();
  InitNees out;
  const Vec2 el = e.tail<2>();
  out.gross = std::abs(el(0)) > 0.25 || std::abs(el(1)) > 10.0 * std::numbers::pi / 180.0;
  out.line = el.dot(c.bottomRightCorner<2, 2>().ldlt().solve(el));
  out.joint = e.dot(c.ldlt().solve(e));
  return out;
}

std::vector<Step> RunOnce(uint64_t seed, double minutes, int ring, int capacity, int& sonar_lines,
                          int& laser_lines, std::vector<InitNees>& init_nees) {
  CorridorRun run(seed, ring);
  SonarLocalMap sonar(SimulatedMapOptions(RangeSensors::kSonar, capacity, run.wheel, run.sonar));
  SonarLocalMap laser(SimulatedMapOptions(RangeSensors::kLaser, capacity, run.wheel, run.sonar));
  const double dt = mc::kOdometryDt;
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
    if (s % mc::kScanEvery != 0) continue;  // 10 Hz sonar readings and laser scans
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
    st.sonar_nees = PoseNees(sonar.RobotPose(), st.truth);
    st.laser_nees = PoseNees(laser.RobotPose(), st.truth);
    out.push_back(st);
  }
  sonar_lines = sonar.Complexity();
  laser_lines = laser.Complexity();
  return out;
}

void AddRelativeErrors(const std::vector<Step>& steps, int gap, Pose2 Step::*which,
                       std::vector<double>& trans, std::vector<double>& rot) {
  for (size_t i = 0; i + gap < steps.size(); i += gap) {
    AddPairError(Between(steps[i].truth, steps[i + gap].truth),
                 Between(steps[i].*which, steps[i + gap].*which), trans, rot);
  }
}

int RunMcMode(const cli::ToolOptions& args) {
  const McDefaults d;
  double minutes = d.minutes;
  int runs = d.runs, ring = d.ring, seed = d.seed, capacity = d.capacity;
  std::string error;
  if (!GetIntegerOption(args, "--runs", 1, 10000, runs, error) ||
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
                          static_cast<int>(capacity), sl, ll, init_nees));
    sonar_lines += sl;
    laser_lines += ll;
    std::fprintf(stderr, "\rrun %d/%d done (%d sonar lines, %d laser lines)   ", r + 1, n, sl, ll);
  }
  std::fprintf(stderr, "\n");
  size_t steps = all[0].size();
  for (const auto& a : all) steps = std::min(steps, a.size());
  const mc::NeesBand band = mc::MeanNeesBand(3, n);
  std::printf(
      "corridor 20 m x 2.4 m, %d runs x %.1f min, %d-transducer ring (specular misses, "
      "multipath), capacity %d; mean final lines: sonar %.1f, laser %.1f\n",
      n, minutes, static_cast<int>(ring), static_cast<int>(capacity), sonar_lines / n,
      laser_lines / n);
  for (const auto& [name, field] :
       {std::pair{"sonar-only", &Step::sonar_nees}, std::pair{"laser-only", &Step::laser_nees}}) {
    std::vector<std::vector<double>> nees(all.size());
    for (size_t r = 0; r < all.size(); ++r)
      for (const Step& st : all[r]) nees[r].push_back(st.*field);
    const mc::BandSummary s = mc::SummarizeInBand(mc::MeanPerStep(nees), band);
    std::printf(
        "  robot NEES %-10s: 95%% band [%.2f, %.2f]; mean %.2f, max %.2f; steps inside "
        "%d/%d = %.1f%%, below the upper bound %.1f%%\n",
        name, band.lo, band.hi, s.mean, s.max, s.inside, s.steps, s.InsidePercent(),
        s.BelowPercent());
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
        "  sonar lines at initialisation (delayed states): %zu within 0.25 m and 10 deg of their "
        "nearest "
        "wall (+%d farther); line NEES (2 dof) mean %.2f, above the 95%% bound %.1f%%; robot+line "
        "NEES (5 dof) mean %.2f, above the 95%% bound %.1f%%\n",
        line.size(), gross, ls.mean, 100.0 * line_out / k, js.mean, 100.0 * joint_out / k);
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

}  // namespace

cli::ToolMode McMode() {
  const McDefaults d;
  return {
      "mc",
      "sonar-only and laser-only local maps in a simulated corridor: NEES, errors",
      {{"--runs", "N", "runs, noise seeds S..S+N-1 (default " + std::to_string(d.runs) + ")"},
       {"--minutes", "M", "minutes driven per run (default " + cli::HelpNumber(d.minutes) + ")"},
       RingOption(d.ring),
       {"--seed", "S", "the first run's noise seed (default " + std::to_string(d.seed) + ")"},
       {"--capacity", "C",
        "map capacity of both maps (default " + std::to_string(d.capacity) + ")"}},
      RunMcMode};
}

}  // namespace atlas::sonar_eval
