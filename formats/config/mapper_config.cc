#include "formats/config/mapper_config.h"

#include <cmath>

#include "drivers/p2os/p2os_messages.h"

namespace atlas {
namespace {
constexpr double kDegToRad = M_PI / 180.0;
}  // namespace

std::vector<SonarTransducer> SonarRingOf(SonarRing ring) {
  return ring == SonarRing::kB21_24 ? p2os::B21SonarRing() : p2os::P3dxSonarRing();
}

MapperSettings ToMapperSettings(const DaemonOptions& o) {
  MapperSettings s;
  AtlasOptions& a = s.atlas;
  a.max_hypotheses = o.atlas.max_hypotheses;
  a.lifecycle.probation_scans = o.atlas.probation_steps;
  a.lifecycle.switch_margin = o.atlas.switch_margin;
  a.quality.alpha = o.atlas.quality_alpha;
  a.quality.sigma_x = o.atlas.max_sigma_x;
  a.quality.sigma_y = o.atlas.max_sigma_y;
  a.quality.sigma_theta = o.atlas.max_sigma_theta;
  a.projection_max_frames = o.atlas.frames_examined_per_step;
  a.match_candidates_per_step = o.atlas.match_candidates_per_step;
  LocalMapOptions& m = s.local_map;
  m.capacity = o.atlas.map_capacity;
  const OdometryErrorConfig& n = o.noise.odometry;
  m.odometry.track_width = o.odometry.track_width_m;
  m.odometry.wheel_var_per_m = n.wheel_sigma_per_m * n.wheel_sigma_per_m;
  m.odometry.xy_var_per_m = n.translation_sigma_per_m * n.translation_sigma_per_m;
  m.odometry.xy_var_per_rad = n.translation_sigma_per_rad * n.translation_sigma_per_rad;
  m.odometry.theta_var_per_m = n.rotation_sigma_per_m * n.rotation_sigma_per_m;
  m.odometry.theta_var_per_rad = n.rotation_sigma_per_rad * n.rotation_sigma_per_rad;
  m.odometry.wheel_scale_sigma = n.wheel_scale_sigma;
  m.odometry.track_width_sigma = n.track_width_sigma;
  m.extraction.range_sigma = o.noise.laser.range_sigma_m;
  m.extraction.model_sigma = o.noise.laser.wall_sigma_m;
  m.extraction.min_rho_sigma = o.noise.laser.line_rho_sigma_min_m;
  m.extraction.min_alpha_sigma = o.noise.laser.line_alpha_sigma_min_deg * kDegToRad;
  s.sensors = o.localmap.sensors;
  if (s.sensors != RangeSensors::kLaser) s.sonar_ring = SonarRingOf(o.sonar.ring);
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
  l.laser_time_offset = FromSeconds(o.laser.time_offset_s).time_since_epoch();
  return l;
}

std::string ValidateMapperOptions(const DaemonOptions& o) {
  std::string out;
  auto add = [&out](const char* what, const std::string& e) {
    if (!e.empty()) out += std::string(what) + ": " + e + "\n";
  };
  add("atlas", ValidateMapperSettings(ToMapperSettings(o)));
  add("loop", ToStepLoopOptions(o).Validate());
  return out;
}

}  // namespace atlas
