#include "core/localmap/fake_wall_scanner.h"

#include <cmath>

#include "core/localmap/line_model.h"

namespace atlas {

FakeWallScanner::FakeWallScanner(std::vector<Wall> walls, const FakeLaserOptions& options,
                                 uint64_t seed)
    : walls_(std::move(walls)), options_(options), rng_(seed) {}

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
    const Vec2 d(std::cos(phi), std::sin(phi));
    double best = options_.max_range;
    int best_wall = -1;
    for (int w = 0; w < static_cast<int>(walls_.size()); ++w) {
      const Vec2 e = walls_[w].b - walls_[w].a;
      const double den = d.x() * e.y() - d.y() * e.x();
      if (std::abs(den) < 1e-12) continue;
      const Vec2 ao = walls_[w].a - o;
      const double t = (ao.x() * e.y() - ao.y() * e.x()) / den;  // along the beam
      const double u = (ao.x() * d.y() - ao.y() * d.x()) / den;  // along the wall
      if (t > 1e-6 && u >= 0.0 && u <= 1.0 && t < best) {
        best = t;
        best_wall = w;
      }
    }
    if (best_wall < 0) continue;
    const double r = best + options_.range_sigma * normal_(rng_);
    if (r <= 0.0 || r >= options_.max_range) continue;
    scan.ranges[i] = static_cast<float>(r);
    if (hit_wall != nullptr) (*hit_wall)[i] = best_wall;
  }
  return scan;
}

Vec2 FakeWallScanner::WallLine(const Wall& w) {
  const Vec2 e = w.b - w.a;
  double alpha = std::atan2(e.x(), -e.y());  // normal direction
  double rho = w.a.x() * std::cos(alpha) + w.a.y() * std::sin(alpha);
  CanonicalizeLine(rho, alpha);
  return Vec2(rho, alpha);
}

std::vector<Wall> CorridorWorld(double length, double width) {
  const double h = 0.5 * width;
  std::vector<Wall> w;
  // End walls.
  w.push_back({Vec2(-1.0, -h), Vec2(-1.0, h)});
  w.push_back({Vec2(length + 1.0, -h), Vec2(length + 1.0, h)});
  // Side walls with door recesses (0.3 m deep) every ~7 m, alternating sides.
  const double door = 1.0, depth = 0.3;
  for (int side = 0; side < 2; ++side) {
    const double y = side == 0 ? h : -h;
    const double out = side == 0 ? h + depth : -h - depth;
    double x = -1.0;
    double next_door = side == 0 ? 4.0 : 7.5;
    while (next_door + door < length) {
      w.push_back({Vec2(x, y), Vec2(next_door, y)});
      w.push_back({Vec2(next_door, y), Vec2(next_door, out)});
      w.push_back({Vec2(next_door, out), Vec2(next_door + door, out)});
      w.push_back({Vec2(next_door + door, out), Vec2(next_door + door, y)});
      x = next_door + door;
      next_door += 7.0;
    }
    w.push_back({Vec2(x, y), Vec2(length + 1.0, y)});
  }
  // A pillar (square, 0.4 m) standing off the north wall half way.
  const double px = 0.5 * length, py = h - 0.5;
  w.push_back({Vec2(px, py), Vec2(px + 0.4, py)});
  w.push_back({Vec2(px + 0.4, py), Vec2(px + 0.4, h)});
  w.push_back({Vec2(px, py), Vec2(px, h)});
  return w;
}

}  // namespace atlas
