#pragma once
// A SICK LMS-like planar laser: beams evenly over the field of view, the first at -fov/2
// (counter-clockwise order, as CARMEN FLASER), each the first wall hit along its ray plus
// Gaussian range noise. Beyond max_range, and with a small random dropout probability, a beam
// has no return (kNoReturn). Moving obstacles (discs) are hit as the walls are.

#include <span>
#include <string>
#include <vector>

#include "core/common/sensor_types.h"
#include "sim/fast_noise.h"
#include "sim/ray_caster.h"

namespace atlas::sim {

struct LaserOptions {
  int beams = 181;  // 181 (1 deg) or 361 (0.5 deg) over 180 deg
  double fov_deg = 180.0;
  double max_range = 30.0;    // m
  double range_sigma = 0.01;  // m, standard deviation of the range noise
  double dropout_probability = 0.002;
  double rate_hz = 10.0;  // scans per second
  Pose2 mount;            // the laser on the robot

  std::string Validate() const;
};

class LaserModel {
 public:
  LaserModel(const LaserOptions& options, uint64_t seed);
  // A scan taken from the robot at `robot` (world frame), stamped `stamp`; `obstacles`
  // (people's legs) are seen as well as the walls.
  LaserScan Scan(const RayCaster& caster, const Pose2& robot, Time stamp,
                 std::span<const Disc> obstacles = {});

 private:
  LaserOptions o_;
  FastNoise noise_;
  std::vector<Vec2> beam_dirs_;  // unit beam directions in the sensor frame
};

}  // namespace atlas::sim
