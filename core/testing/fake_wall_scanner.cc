#include "core/testing/fake_wall_scanner.h"

#include <cmath>

namespace atlas {

LocalMapOptions FakeWallMapOptions() {
  LocalMapOptions o;
  o.extraction.model_sigma = 0.0;
  o.extraction.min_rho_sigma = 0.0;
  o.extraction.min_alpha_sigma = 0.0;
  o.odometry.track_width = 0.4;
  o.odometry.wheel_var_per_m = 5e-6;
  o.odometry.xy_var_per_m = 1e-6;
  o.odometry.xy_var_per_rad = 1e-6;
  o.odometry.theta_var_per_m = 1e-6;
  o.odometry.theta_var_per_rad = 1e-5;
  return o;
}

FakeWallScanner::FakeWallScanner(const std::vector<sim::Wall>& walls,
                                 const FakeLaserOptions& options, uint64_t seed)
    : caster_(walls), options_(options), rng_(seed) {}

LaserScan FakeWallScanner::Scan(const Pose2& robot, std::vector<int>* hit_wall) {
  LaserScan scan;
  scan.sensor_pose = options_.sensor_pose;
  scan.max_range = static_cast<float>(options_.max_range);
  scan.angle_increment =
      static_cast<float>(options_.beams > 1 ? options_.fov / (options_.beams - 1) : 0.0);
  scan.angle_min = static_cast<float>(-0.5 * options_.fov);
  scan.ranges.assign(options_.beams, kNoReturn);
  if (hit_wall != nullptr) hit_wall->assign(options_.beams, -1);
  const Pose2 sensor = Compose(robot, options_.sensor_pose);
  const Vec2 o(sensor.x, sensor.y);
  for (int i = 0; i < options_.beams; ++i) {
    const double phi =
        sensor.theta + scan.angle_min + i * static_cast<double>(scan.angle_increment);
    const sim::RayHit hit = caster_.Cast(o, Vec2(std::cos(phi), std::sin(phi)), options_.max_range);
    if (!hit.hit() || !(hit.range < options_.max_range)) continue;
    const double r = hit.range + options_.range_sigma * normal_(rng_);
    if (r <= 0.0 || r >= options_.max_range) continue;
    scan.ranges[i] = static_cast<float>(r);
    if (hit_wall != nullptr) (*hit_wall)[i] = hit.wall;
  }
  return scan;
}

}  // namespace atlas
