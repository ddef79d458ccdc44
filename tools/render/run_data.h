#pragma once
// A simulated run as atlas-sim writes it (docs/formats.md, "Simulated run"), read back for
// drawing: the world, the ground truth, the odometry and a thinned-out set of laser scans.

#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "core/common/sensor_types.h"
#include "sim/world.h"

namespace atlas::draw {

struct RunScan {
  Time stamp{};
  Pose2 laser_in_odometry;  // FLASER x y theta
  Pose2 robot_odometry;     // FLASER odom_x odom_y odom_theta
  double angle_min = 0.0;
  double angle_increment = 0.0;
  std::vector<float> ranges;  // metres or kNoReturn
};

struct RunData {
  sim::World world;
  std::vector<TruthSample> truth;
  std::vector<OdometrySample> odometry;
  std::vector<RunScan> scans;  // every scan_stride-th FLASER line
  long total_scans = 0;
  long scan_stride = 1;
  long sonar_lines = 0;
};

struct RunReadOptions {
  // Keep at most about this many scans, evenly spread over the run (the stride doubles as the
  // run grows).
  long max_scans = 500;
};

// Reads DIR/world.txt, DIR/truth.tsv (a pose file, formats/pose_file.h) and DIR/run.clf.
// Returns "" or what is wrong (file, line). All three are required; truth.tsv must hold rows.
std::string ReadRun(const std::string& dir, const RunReadOptions& options, RunData* run);

// The pose of `truth` interpolated at `stamp` (clamped to the ends); truth must be non-empty
// and time-ordered.
Pose2 InterpolateTruth(const std::vector<TruthSample>& truth, Time stamp);

// The world-frame end points of a scan's returns, the laser at `laser_pose`.
std::vector<Vec2> ScanPoints(const RunScan& scan, const Pose2& laser_pose);

}  // namespace atlas::draw
