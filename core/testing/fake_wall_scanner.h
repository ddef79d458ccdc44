#pragma once
// A fake laser for tests: the simulator's ray caster (sim/ray_caster.h) against wall segments,
// plus seeded Gaussian range noise. It knows which wall each beam hit, so that tests can tie
// extracted lines to true lines (LineThroughPoints of the wall, core/localmap/line_model.h).

#include <cstdint>
#include <random>
#include <vector>

#include "core/common/sensor_types.h"
#include "core/localmap/localmap_options.h"
#include "sim/ray_caster.h"

namespace atlas {

struct FakeLaserOptions {
  int beams = 361;
  double fov = 3.14159265358979323846;  // radians, centred on the sensor's x axis
  double max_range = 30.0;
  double range_sigma = 0.01;
  Pose2 sensor_pose;  // mounting
};

class FakeWallScanner {
 public:
  FakeWallScanner(const std::vector<sim::Wall>& walls, const FakeLaserOptions& options,
                  uint64_t seed);

  // A scan from the robot at `robot` (world frame). hit_wall[i] is the wall beam i hit, or -1.
  LaserScan Scan(const Pose2& robot, std::vector<int>* hit_wall = nullptr);

 private:
  sim::RayCaster caster_;
  FakeLaserOptions options_;
  std::mt19937_64 rng_;
  std::normal_distribution<double> normal_{0.0, 1.0};
};

// The line local map for the fake scanner: its walls are straight and its range noise is the
// model's, so the line fits get no wall noise and no floors (core/localmap's defaults are a real
// building's), and the odometry noise is a small, well calibrated base's (track 0.4 m; per metre
// 5e-6 m^2 each wheel, 1e-6 m^2 in x and y, 1e-6 rad^2; per radian 1e-6 m^2, 1e-5 rad^2), which
// the tests' scripts are written for.
LocalMapOptions FakeWallMapOptions();

}  // namespace atlas
