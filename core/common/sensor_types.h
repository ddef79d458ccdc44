#pragma once
// Plain sensor data, as every source delivers it to core/: the CARMEN reader, the simulator,
// the device drivers and the LCM replay. No I/O types appear here.

#include <cmath>
#include <limits>
#include <variant>
#include <vector>

#include "core/common/time.h"
#include "core/geometry/se2.h"

namespace atlas {

// A laser range that carries no return (no echo, dazzle, out of range). Test with IsReturn().
inline constexpr float kNoReturn = std::numeric_limits<float>::infinity();
inline bool IsReturn(float range) { return std::isfinite(range); }

// Cumulative wheel odometry: the dead-reckoned pose of the base in its odometry frame, as the
// base reports it at `stamp`. Consumers use differences of consecutive samples only.
struct OdometrySample {
  Time stamp{};
  Pose2 pose;
  // As the base reported them, where it does (0 otherwise): cumulative wheel distances, metres,
  // and its velocities, m/s and rad/s. Carried to the raw-odometry output only.
  double left_m = 0.0;
  double right_m = 0.0;
  double linear_velocity = 0.0;
  double angular_velocity = 0.0;
};

// One planar laser scan. Beam i has bearing angle_min + i * angle_increment in the sensor
// frame (counter-clockwise, radians). `sensor_pose` is the sensor's mounting pose on the robot.
struct LaserScan {
  Time stamp{};
  float angle_min = 0.0f;
  float angle_increment = 0.0f;
  float max_range = 0.0f;     // metres; the sensor's maximum
  std::vector<float> ranges;  // metres, or kNoReturn
  Pose2 sensor_pose;          // the sensor on the robot
};

// Applies a range setting to a scan: returns at or beyond `max_range` (metres, > 0) become
// kNoReturn, and the scan's max_range becomes the smaller of its own and `max_range` (its own
// when that is not positive). The scanner's maximum is the sensor's, not a mapping limit.
inline void LimitLaserRange(LaserScan* scan, float max_range) {
  for (float& r : scan->ranges)
    if (!(r < max_range)) r = kNoReturn;
  if (!(scan->max_range > 0.0f) || max_range < scan->max_range) scan->max_range = max_range;
}

// Sonar returns fired since the previous reading. Ranges in metres; a transducer that saw
// nothing within its maximum range reports kNoReturn. Geometry (mounting pose, beam width) is
// configuration, looked up by transducer index.
struct SonarReturn {
  int transducer = 0;
  float range = kNoReturn;
};
struct SonarReading {
  Time stamp{};
  std::vector<SonarReturn> returns;
};

// Mounting of one sonar transducer on the robot.
struct SonarTransducer {
  Pose2 pose;                  // x, y (m) and heading (rad) on the robot
  double beam_width = 0.4363;  // full cone angle, radians (25 degrees)
  double max_range = 5.0;      // metres
};

// Ground truth or a reference trajectory (simulator, corrected logs), never fed to the atlas.
struct TruthSample {
  Time stamp{};
  Pose2 pose;
};

using SensorEvent = std::variant<OdometrySample, LaserScan, SonarReading>;

inline Time StampOf(const SensorEvent& e) {
  return std::visit([](const auto& v) { return v.stamp; }, e);
}

}  // namespace atlas
