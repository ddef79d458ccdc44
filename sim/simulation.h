#pragma once
// One simulated run: a robot drives a route through a world, and the sensors report.
//
// Time runs from `start_time` in steps of 1 / odometry_hz. Each step the true pose advances
// (DiffDriveFollower), the wheel-odometry model reports (WheelOdometryModel), and laser scans
// and sonar readings fall due at their own rates; a sensor stamped between two steps sees the
// true pose interpolated to its stamp. Everything random is drawn from generators seeded from
// `seed`, so a run is reproducible. Events reach the sink in stamp order. The world's people
// walk from the first stamp on; the laser sees their legs, the sonar does not.

#include <cstdint>
#include <functional>
#include <memory>
#include <string>

#include "core/common/sensor_types.h"
#include "sim/laser_model.h"
#include "sim/ray_caster.h"
#include "sim/route.h"
#include "sim/sonar_model.h"
#include "sim/wheel_odometry_model.h"
#include "sim/world.h"

namespace atlas::sim {

struct SimulationOptions {
  double length_m = 1000.0;   // the run ends when the robot has driven this far
  double odometry_hz = 50.0;  // also the rate of the ground truth
  double start_time = 0.0;    // seconds, stamp of the first sample
  bool laser = true;
  bool sonar = false;
  LaserOptions laser_options;
  SonarOptions sonar_options;
  WheelOdometryNoiseOptions odometry_options;
  MotionOptions motion_options;
  uint64_t seed = 1;

  std::string Validate() const;
};

class SimulationSink {
 public:
  virtual ~SimulationSink() = default;
  virtual void OnTruth(const TruthSample& truth) = 0;
  virtual void OnOdometry(const OdometrySample& odometry, double speed, double turn_rate) = 0;
  // `odometry` is the odometry pose interpolated to the scan's stamp.
  virtual void OnLaser(const LaserScan& scan, const Pose2& odometry) = 0;
  virtual void OnSonar(const SonarReading& reading, const Pose2& odometry) = 0;
};

struct SimulationSummary {
  double distance_m = 0.0;
  double duration_s = 0.0;
  long truth_samples = 0;
  long laser_scans = 0;
  long sonar_readings = 0;
  long route_waypoints = 0;
  std::string error;  // non-empty if the run could not start (e.g. no route in the world)
};

// Where a run starts: the corridor node of degree >= 2 nearest the middle of the world's
// bounding box (so that there are loops on all sides), or -1 if the world has none.
int StartNode(const World& world);

// Runs the whole simulation. `progress` (may be empty) is called now and then with the
// distance driven so far.
SimulationSummary Simulate(const World& world, const SimulationOptions& options,
                           SimulationSink& sink,
                           const std::function<void(double distance_m)>& progress = {});

}  // namespace atlas::sim
