#pragma once
// One simulated run in the Monte Carlo corridor (tools/monte_carlo/corridor.h) with the sonar
// ring, a laser and wheel odometry without calibration errors; stepped by the caller
// (atlas-sonar-eval mc and fig9).

#include <cstdint>
#include <vector>

#include "sim/laser_model.h"
#include "sim/ray_caster.h"
#include "sim/route.h"
#include "sim/sonar_model.h"
#include "sim/wheel_odometry_model.h"
#include "tools/cli/tool_modes.h"

namespace atlas::sonar_eval {

// The largest --seed of the modes (seeds S..S+N-1 are printed as int).
inline constexpr int kMaxSeed = 1000000000;

// The simulated sonar with the P3-DX's 16-transducer ring (`ring` 16) or the B21's 24.
sim::SonarOptions SonarOptionsFor(int ring);
// The modes' --ring option (16 or 24 transducers, as SonarOptionsFor), default `ring`.
cli::ToolModeOption RingOption(int ring);

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

  CorridorRun(uint64_t seed, int ring);
};

}  // namespace atlas::sonar_eval
