#include "daemon/atlasd/daemon_setup.h"

#include <cmath>

namespace atlas {
namespace {
constexpr double kDegToRad = M_PI / 180.0;

// The driver threads run at the loop's real-time priority (SCHED_FIFO) when the loop has one:
// the arrival stamp and the wake-up of the loop are on the pose's latency path.
int ReaderPriority(const DaemonOptions& o) {
  return o.scheduling.policy == SchedPolicy::kOther ? 0 : o.scheduling.priority;
}

// The scanner on the robot (laser.mount).
Pose2 LaserMount(const DaemonOptions& o) {
  return Pose2{o.laser.mount.x_m, o.laser.mount.y_m, o.laser.mount.theta_deg * kDegToRad};
}

}  // namespace

LaserReaderOptions ToLaserReaderOptions(const DaemonOptions& o) {
  LaserReaderOptions l;
  l.device = o.laser.device;
  l.baud = o.laser.baud;
  l.angle_deg = static_cast<uint16_t>(o.laser.angular_range_deg);
  l.resolution_centideg = static_cast<uint16_t>(std::lround(o.laser.angular_resolution_deg * 100));
  l.unit = o.laser.unit;
  l.max_range = static_cast<float>(o.laser.max_range_m);
  l.sensor_pose = LaserMount(o);
  l.queue_capacity = static_cast<size_t>(o.laser.queue_capacity);
  l.reconnect.realtime_priority = ReaderPriority(o);
  return l;
}

OdometryReaderOptions ToOdometryReaderOptions(const DaemonOptions& o) {
  OdometryReaderOptions r;
  r.interface_name = o.odometry.interface;
  r.odometry.track_width_m = o.odometry.track_width_m;
  r.odometry.max_speed_mps = o.odometry.max_speed_mps;
  r.odometry.slack_m = o.odometry.slack_m;
  r.odometry.max_gap_s = o.odometry.max_gap_s;
  r.queue_capacity = static_cast<size_t>(o.odometry.queue_capacity);
  r.reconnect.realtime_priority = ReaderPriority(o);
  return r;
}

SonarReaderOptions ToSonarReaderOptions(const DaemonOptions& o) {
  SonarReaderOptions s;
  s.device = o.sonar.device;
  // The configured rate first after the power-up rate.
  s.probe_rates = {9600};
  for (int b : {o.sonar.baud, 19200, 38400, 57600, 115200})
    if (std::find(s.probe_rates.begin(), s.probe_rates.end(), b) == s.probe_rates.end())
      s.probe_rates.push_back(b);
  s.sonar.range_factor_mm = o.sonar.range_factor_mm;
  s.sonar.ring = SonarRingOf(o.sonar.ring);
  s.queue_capacity = static_cast<size_t>(o.sonar.queue_capacity);
  s.reconnect.realtime_priority = ReaderPriority(o);
  return s;
}

LcmInputOptions ToLcmInputOptions(const DaemonOptions& o) {
  LcmInputOptions i;
  i.url = o.lcm.url;
  i.laser_enabled = o.laser.enabled;
  i.laser_type = o.input.laser_type;
  i.odometry_type = o.input.odometry_type;
  i.laser_channel = o.input.laser_channel;
  i.odometry_channel = o.input.odometry_channel;
  i.laser.sensor_pose = LaserMount(o);
  i.laser.max_range = static_cast<float>(o.laser.max_range_m);
  i.laser_queue_capacity = static_cast<size_t>(o.laser.queue_capacity);
  i.odometry_queue_capacity = static_cast<size_t>(o.odometry.queue_capacity);
  i.realtime_priority = ReaderPriority(o);
  return i;
}

std::string ValidateDerivedOptions(const DaemonOptions& o) {
  std::string out;
  auto add = [&out](const char* what, const std::string& e) {
    if (!e.empty()) out += std::string(what) + ": " + e + "\n";
  };
  out += ValidateMapperOptions(o);
  if (o.input.source == InputSource::kLcm) {
    add("input", ToLcmInputOptions(o).Validate());
    return out;
  }
  if (o.laser.enabled) add("laser", ToLaserReaderOptions(o).Validate());
  add("odometry", ToOdometryReaderOptions(o).Validate());
  if (o.sonar.enabled) add("sonar", ToSonarReaderOptions(o).Validate());
  return out;
}

}  // namespace atlas
