#pragma once
// A route through a world and the robot's motion along it.
//
// PlanRoute walks the world's route graph: at each node it picks among the edges not leading
// straight back (unless it is a dead end, e.g. a room centre) with weight
// 1 / (1 + times driven)^2, doubled for going straight on. The walk thus spreads over the whole
// building, drives round loops of every size, enters rooms through their doors and comes back to
// places it has seen: the loop closures an atlas must find.
//
// DiffDriveFollower drives a differential-drive robot through the waypoints: it turns toward
// the next waypoint (turning in place when the heading error is large), with speed, turn-rate
// and acceleration limits, slowing down before sharp corners. Each step integrates an exact arc.

#include <cstdint>
#include <random>
#include <string>
#include <vector>

#include "sim/world.h"

namespace atlas::sim {

// Waypoints (node ids) of a walk at least `length_m` long, starting at node `start`.
// Empty if the graph has no edges at `start`.
std::vector<int> PlanRoute(const World& world, double length_m, int start, uint64_t seed);

struct MotionOptions {
  double max_speed = 0.8;            // m/s
  double max_turn_rate = 1.0;        // rad/s
  double max_accel = 0.6;            // m/s^2
  double max_turn_accel = 3.0;       // rad/s^2
  double heading_gain = 2.5;         // 1/s, turn rate per radian of heading error
  double drive_heading_error = 0.6;  // rad; above this the robot turns in place

  std::string Validate() const;
};

class DiffDriveFollower {
 public:
  // Starts at the first waypoint, facing the second.
  DiffDriveFollower(const MotionOptions& options, std::vector<Vec2> waypoints);

  // Advances by dt seconds. Returns false once the last waypoint is reached.
  bool Step(double dt);

  const Pose2& pose() const { return pose_; }
  double speed() const { return v_; }
  double turn_rate() const { return w_; }
  double distance() const { return distance_; }  // travelled so far, metres

 private:
  MotionOptions o_;
  std::vector<Vec2> waypoints_;
  size_t target_ = 1;
  Pose2 pose_;
  double v_ = 0.0, w_ = 0.0, distance_ = 0.0;
};

}  // namespace atlas::sim
