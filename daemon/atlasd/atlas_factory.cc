#include "daemon/atlasd/atlas_factory.h"

#include "core/atlas/line_map_bootstrapper.h"
#include "core/localmap/line_ekf_map.h"
#include "core/localmap/localmap_options.h"

namespace atlas {
namespace {

LocalMapOptions ToLocalMapOptions(const MapperSettings& s) {
  LocalMapOptions o;
  o.capacity = s.map_capacity;
  o.odometry = s.odometry;
  o.extraction.range_sigma = s.laser_range_sigma_m;
  o.extraction.model_sigma = s.wall_sigma_m;
  o.extraction.min_rho_sigma = s.line_rho_sigma_min_m;
  o.extraction.min_alpha_sigma = s.line_alpha_sigma_min_rad;
  o.quality.alpha = s.quality_alpha;
  o.quality.max_sigma_x = s.max_sigma_x;
  o.quality.max_sigma_y = s.max_sigma_y;
  o.quality.max_sigma_theta = s.max_sigma_theta;
  return o;
}

AtlasOptions ToAtlasOptions(const MapperSettings& s) {
  AtlasOptions o;
  o.max_hypotheses = s.max_hypotheses;
  o.lifecycle.probation_scans = std::max(s.probation_steps, o.lifecycle.bootstrap_scans + 1);
  o.quality.alpha = s.quality_alpha;
  o.quality.sigma_x = s.max_sigma_x;
  o.quality.sigma_y = s.max_sigma_y;
  o.quality.sigma_theta = s.max_sigma_theta;
  o.projection_max_frames = s.frames_examined_per_step;
  o.match_candidates_per_step = s.match_candidates_per_step;
  return o;
}

}  // namespace

std::string ValidateMapperSettings(const MapperSettings& s) {
  if (std::string e = ToLocalMapOptions(s).Validate(); !e.empty()) return "local map: " + e;
  if (std::string e = ToAtlasOptions(s).Validate(); !e.empty()) return "atlas: " + e;
  return "";
}

std::unique_ptr<Atlas> MakeAtlas(const MapperSettings& s) {
  const LocalMapOptions map_options = ToLocalMapOptions(s);
  return std::make_unique<Atlas>(
      ToAtlasOptions(s), [map_options]() { return std::make_unique<LineEkfMap>(map_options); },
      std::make_shared<LineMapBootstrapper>(map_options));
}

Mat3 OdometryIncrementNoise(const Pose2& delta, const MapperSettings& s) {
  return LineEkfMap::OdometryNoise(delta, ToLocalMapOptions(s).odometry);
}

}  // namespace atlas
