#pragma once
// A fake laser for tests and evaluation: exact ray casting against wall segments plus seeded
// Gaussian range noise. It knows which wall each beam hit, so that tests can tie extracted
// lines to true lines. Pure computation.

#include <cstdint>
#include <random>
#include <vector>

#include "core/common/sensor_types.h"

namespace atlas {

struct Wall {
  Vec2 a;
  Vec2 b;
};

struct FakeLaserOptions {
  int beams = 361;
  double fov = 3.14159265358979323846;  // radians, centred on the sensor's x axis
  double max_range = 30.0;
  double range_sigma = 0.01;
  Pose2 sensor_pose;  // mounting
};

class FakeWallScanner {
 public:
  FakeWallScanner(std::vector<Wall> walls, const FakeLaserOptions& options, uint64_t seed);

  // A scan from the robot at `robot` (world frame). hit_wall[i] is the wall beam i hit, or -1.
  LaserScan Scan(const Pose2& robot, std::vector<int>* hit_wall = nullptr);

  const std::vector<Wall>& Walls() const { return walls_; }

  // The wall's infinite line in canonical (rho, alpha) form in the world frame.
  static Vec2 WallLine(const Wall& w);

 private:
  std::vector<Wall> walls_;
  FakeLaserOptions options_;
  std::mt19937_64 rng_;
  std::normal_distribution<double> normal_{0.0, 1.0};
};

// A corridor world: a straight corridor of `length` x `width` metres along +x from the origin
// with closed ends and a few door recesses and pillars that break the side walls, giving
// lines in three directions.
std::vector<Wall> CorridorWorld(double length = 30.0, double width = 2.4);

}  // namespace atlas
