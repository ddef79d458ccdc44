#include "core/mapper/mapper_factory.h"

#include "core/atlas/line_map_bootstrapper.h"
#include "core/gridmap/grid_map_bootstrapper.h"
#include "core/gridmap/grid_map_matcher.h"
#include "core/localmap/line_ekf_map.h"
#include "core/localmap/localmap_options.h"
#include "core/sonar/sonar_local_map.h"
#include "core/sonar/sonar_map_bootstrapper.h"

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

GridLocalMapOptions ToGridMapOptions(const MapperSettings& s) {
  GridLocalMapOptions o;
  o.odometry = s.odometry;
  return o;
}

bool GridFrames(const MapperSettings& s) {
  return s.grid_frames && s.sensors == RangeSensors::kLaser;
}

AtlasOptions ToAtlasOptions(const MapperSettings& s) {
  AtlasOptions o;
  o.max_hypotheses = s.max_hypotheses;
  o.lifecycle.probation_scans = std::max(s.probation_steps, o.lifecycle.bootstrap_scans + 1);
  o.lifecycle.switch_margin = s.switch_margin;
  o.quality.alpha = s.quality_alpha;
  o.quality.sigma_x = s.max_sigma_x;
  o.quality.sigma_y = s.max_sigma_y;
  o.quality.sigma_theta = s.max_sigma_theta;
  o.projection_max_frames = s.frames_examined_per_step;
  o.match_candidates_per_step = s.match_candidates_per_step;
  if (s.sensors == RangeSensors::kSonar) {
    o.match = SonarMapMatchOptions(o.match);
    if (s.sonar_bootstrap)
      o.lifecycle.probation_scans = std::max(o.lifecycle.probation_scans, kSonarBootstrapProbation);
  } else {
    o.match = LaserMapMatchOptions(o.match);
    // Measured on the six corrected logs (60 seeds) and mit-csail (docs/design.md,
    // "III-C. Genesis" and "III-E. Traversal").
    o.genesis_cov_scale = 2.0;
    o.return_q = 0.9;
    o.return_radius = 4.0;
    o.return_far_radius = 1.5;
    // Condition 2 with the frames' points (docs/design.md, "Points: structure beyond the lines").
    o.points.enabled = true;
  }
  if (GridFrames(s)) {
    // Grids are map-matched by GridMapMatcher, once they hold a few scans; no lines, no points.
    o.points.enabled = false;
    o.min_match_lines = std::max(o.match.min_support, 5);
  }
  return o;
}

SonarLocalMapOptions ToSonarMapOptions(const MapperSettings& s) {
  SonarLocalMapOptions o;
  o.sensors = s.sensors;
  o.ring = s.sonar_ring;
  o.line_map = ToLocalMapOptions(s);
  return o;
}

}  // namespace

std::string ValidateMapperSettings(const MapperSettings& s) {
  if (std::string e = ToLocalMapOptions(s).Validate(); !e.empty()) return "local map: " + e;
  if (s.sensors != RangeSensors::kLaser) {
    if (s.sonar_ring.empty()) return "sonar local map: the sonar ring has no transducer";
    if (std::string e = ToSonarMapOptions(s).Validate(); !e.empty()) return "sonar local map: " + e;
  }
  if (s.grid_frames && s.sensors != RangeSensors::kLaser)
    return "grid local map: maps with the laser alone";
  if (std::string e = ToGridMapOptions(s).Validate(); !e.empty()) return "grid local map: " + e;
  if (std::string e = ToAtlasOptions(s).Validate(); !e.empty()) return "atlas: " + e;
  if (std::string e = s.scan_match.Validate(); !e.empty()) return e;
  return "";
}

std::unique_ptr<Atlas> MakeAtlas(const MapperSettings& s) {
  const LocalMapOptions map_options = ToLocalMapOptions(s);
  if (GridFrames(s)) {
    const GridLocalMapOptions grid = ToGridMapOptions(s);
    auto atlas = std::make_unique<Atlas>(
        ToAtlasOptions(s), [grid]() { return std::make_unique<GridLocalMap>(grid); },
        std::make_shared<GridMapBootstrapper>(grid));
    atlas->SetMapMatcher(std::make_shared<GridMapMatcher>(grid));
    return atlas;
  }
  if (s.sensors == RangeSensors::kLaser) {
    return std::make_unique<Atlas>(
        ToAtlasOptions(s), [map_options]() { return std::make_unique<LineEkfMap>(map_options); },
        std::make_shared<LineMapBootstrapper>(map_options));
  }
  const SonarLocalMapOptions sonar = ToSonarMapOptions(s);
  std::shared_ptr<const PoseBootstrapper> w;
  if (s.sensors == RangeSensors::kBoth) w = std::make_shared<LineMapBootstrapper>(map_options);
  if (s.sensors == RangeSensors::kSonar && s.sonar_bootstrap)
    w = std::make_shared<SonarMapBootstrapper>();
  return std::make_unique<Atlas>(
      ToAtlasOptions(s), [sonar]() { return std::make_unique<SonarLocalMap>(sonar); }, w);
}

Mat3 OdometryIncrementNoise(const Pose2& delta, const MapperSettings& s) {
  return LineEkfMap::OdometryNoise(delta, ToLocalMapOptions(s).odometry);
}

}  // namespace atlas
