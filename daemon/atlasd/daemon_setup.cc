#include "daemon/atlasd/daemon_setup.h"

#include <cmath>

#include "drivers/p2os/p2os_messages.h"

namespace atlas {
namespace {
constexpr double kDegToRad = M_PI / 180.0;

// The driver threads run at the loop's real-time priority (SCHED_FIFO) when the loop has one:
// the arrival stamp and the wake-up of the loop are on the pose's latency path.
int ReaderPriority(const DaemonOptions& o) {
  return o.scheduling.policy == SchedPolicy::kOther ? 0 : o.scheduling.priority;
}

std::vector<SonarTransducer> SonarRingOf(const DaemonOptions& o) {
  return o.sonar.ring == SonarRing::kB21_24 ? p2os::B21SonarRing() : p2os::P3dxSonarRing();
}
}  // namespace

MapperSettings ToMapperSettings(const DaemonOptions& o) {
  MapperSettings s;
  s.map_capacity = o.atlas.map_capacity;
  s.max_hypotheses = o.atlas.max_hypotheses;
  s.probation_steps = o.atlas.probation_steps;
  s.quality_alpha = o.atlas.quality_alpha;
  s.max_sigma_x = o.atlas.max_sigma_x;
  s.max_sigma_y = o.atlas.max_sigma_y;
  s.max_sigma_theta = o.atlas.max_sigma_theta;
  s.frames_examined_per_step = o.atlas.frames_examined_per_step;
  s.match_candidates_per_step = o.atlas.match_candidates_per_step;
  const OdometryErrorConfig& n = o.noise.odometry;
  s.odometry.track_width = o.odometry.track_width_m;
  s.odometry.wheel_var_per_m = n.wheel_sigma_per_m * n.wheel_sigma_per_m;
  s.odometry.xy_var_per_m = n.translation_sigma_per_m * n.translation_sigma_per_m;
  s.odometry.xy_var_per_rad = n.translation_sigma_per_rad * n.translation_sigma_per_rad;
  s.odometry.theta_var_per_m = n.rotation_sigma_per_m * n.rotation_sigma_per_m;
  s.odometry.theta_var_per_rad = n.rotation_sigma_per_rad * n.rotation_sigma_per_rad;
  s.odometry.wheel_scale_sigma = n.wheel_scale_sigma;
  s.odometry.track_width_sigma = n.track_width_sigma;
  s.laser_range_sigma_m = o.noise.laser.range_sigma_m;
  s.wall_sigma_m = o.noise.laser.wall_sigma_m;
  s.line_rho_sigma_min_m = o.noise.laser.line_rho_sigma_min_m;
  s.line_alpha_sigma_min_rad = o.noise.laser.line_alpha_sigma_min_deg * kDegToRad;
  switch (o.localmap.sensors) {
    case LocalMapSensors::kLaser:
      s.sensors = RangeSensors::kLaser;
      break;
    case LocalMapSensors::kSonar:
      s.sensors = RangeSensors::kSonar;
      break;
    case LocalMapSensors::kBoth:
      s.sensors = RangeSensors::kBoth;
      break;
  }
  if (s.sensors != RangeSensors::kLaser) s.sonar_ring = SonarRingOf(o);
  s.sonar_bootstrap = o.localmap.sonar_bootstrap;
  s.grid_frames = o.localmap.kind == LocalMapKind::kGrid;
  s.scan_match.enabled = o.scan_match.enabled;
  s.scan_match.max_range = o.scan_match.max_range_m;
  s.scan_match.point_sigma = o.scan_match.point_sigma_m;
  s.scan_match.information_scale = o.scan_match.information_scale;
  s.scan_match.heading_search = o.scan_match.heading_search_deg * kDegToRad;
  return s;
}

StepLoopOptions ToStepLoopOptions(const DaemonOptions& o) {
  StepLoopOptions l;
  l.step_budget = std::chrono::duration_cast<Duration>(
      std::chrono::duration<double, std::milli>(o.loop.step_budget_ms));
  l.max_pending_scans = o.loop.max_pending_scans;
  l.max_range_m = o.laser.max_range_m;
  l.laser_time_offset = FromSeconds(o.laser.time_offset_s).time_since_epoch();
  return l;
}

LaserReaderOptions ToLaserReaderOptions(const DaemonOptions& o) {
  LaserReaderOptions l;
  l.device = o.laser.device;
  l.baud = o.laser.baud;
  l.angle_deg = static_cast<uint16_t>(o.laser.angular_range_deg);
  l.resolution_centideg = static_cast<uint16_t>(std::lround(o.laser.angular_resolution_deg * 100));
  l.unit =
      o.laser.unit == LaserUnit::kCentimetre ? sick::Unit::kCentimetre : sick::Unit::kMillimetre;
  l.sensor_pose = Pose2{o.laser.mount.x_m, o.laser.mount.y_m, o.laser.mount.theta_deg * kDegToRad};
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
  s.sonar.ring = SonarRingOf(o);
  s.queue_capacity = static_cast<size_t>(o.sonar.queue_capacity);
  s.reconnect.realtime_priority = ReaderPriority(o);
  return s;
}

std::string ValidateDerivedOptions(const DaemonOptions& o) {
  std::string out;
  auto add = [&out](const char* what, const std::string& e) {
    if (!e.empty()) out += std::string(what) + ": " + e + "\n";
  };
  add("atlas", ValidateMapperSettings(ToMapperSettings(o)));
  add("loop", ToStepLoopOptions(o).Validate());
  if (o.laser.enabled) add("laser", ToLaserReaderOptions(o).Validate());
  add("odometry", ToOdometryReaderOptions(o).Validate());
  if (o.sonar.enabled) add("sonar", ToSonarReaderOptions(o).Validate());
  return out;
}

}  // namespace atlas
