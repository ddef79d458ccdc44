#include "core/mapper/mapper_factory.h"

#include "core/atlas/line_map_bootstrapper.h"
#include "core/gridmap/grid_map_bootstrapper.h"
#include "core/gridmap/grid_map_matcher.h"
#include "core/localmap/line_ekf_map.h"
#include "core/sonar/sonar_local_map.h"
#include "core/sonar/sonar_map_bootstrapper.h"

namespace atlas {
namespace {

GridLocalMapOptions ToGridMapOptions(const MapperSettings& s) {
  GridLocalMapOptions o;
  o.odometry = s.local_map.odometry;
  return o;
}

bool GridFrames(const MapperSettings& s) {
  return s.grid_frames && s.sensors == RangeSensors::kLaser;
}

SonarLocalMapOptions ToSonarMapOptions(const MapperSettings& s) {
  SonarLocalMapOptions o;
  o.sensors = s.sensors;
  o.ring = s.sonar_ring;
  o.line_map = LocalMapOptionsOf(s);
  return o;
}

}  // namespace

LocalMapOptions LocalMapOptionsOf(const MapperSettings& s) {
  LocalMapOptions o = s.local_map;
  o.quality.alpha = s.atlas.quality.alpha;
  o.quality.max_sigma_x = s.atlas.quality.sigma_x;
  o.quality.max_sigma_y = s.atlas.quality.sigma_y;
  o.quality.max_sigma_theta = s.atlas.quality.sigma_theta;
  return o;
}

AtlasOptions AtlasOptionsOf(const MapperSettings& s) {
  AtlasOptions o = s.atlas;
  o.lifecycle.probation_scans =
      std::max(o.lifecycle.probation_scans, o.lifecycle.bootstrap_scans + 1);
  if (s.sensors == RangeSensors::kSonar) {
    o = SonarAtlasOptions(o);
    if (s.sonar_bootstrap)
      o.lifecycle.probation_scans = std::max(o.lifecycle.probation_scans, kSonarBootstrapProbation);
  }
  if (GridFrames(s)) {
    // Grids are map-matched by GridMapMatcher, once they hold a few scans; no lines, no points.
    o.points.enabled = false;
    o.min_match_lines = std::max(o.match.min_support, 5);
  }
  return o;
}

std::string ValidateMapperSettings(const MapperSettings& s) {
  if (std::string e = LocalMapOptionsOf(s).Validate(); !e.empty()) return "local map: " + e;
  if (s.sensors != RangeSensors::kLaser) {
    if (s.sonar_ring.empty()) return "sonar local map: the sonar ring has no transducer";
    if (std::string e = ToSonarMapOptions(s).Validate(); !e.empty()) return "sonar local map: " + e;
  }
  if (s.grid_frames && s.sensors != RangeSensors::kLaser)
    return "grid local map: maps with the laser alone";
  if (std::string e = ToGridMapOptions(s).Validate(); !e.empty()) return "grid local map: " + e;
  if (std::string e = AtlasOptionsOf(s).Validate(); !e.empty()) return "atlas: " + e;
  if (std::string e = s.scan_match.Validate(); !e.empty()) return e;
  return "";
}

std::unique_ptr<Atlas> MakeAtlas(const MapperSettings& s) {
  const LocalMapOptions map_options = LocalMapOptionsOf(s);
  if (GridFrames(s)) {
    const GridLocalMapOptions grid = ToGridMapOptions(s);
    auto atlas = std::make_unique<Atlas>(
        AtlasOptionsOf(s), [grid]() { return std::make_unique<GridLocalMap>(grid); },
        std::make_shared<GridMapBootstrapper>(grid));
    atlas->SetMapMatcher(std::make_shared<GridMapMatcher>(grid));
    return atlas;
  }
  if (s.sensors == RangeSensors::kLaser) {
    return std::make_unique<Atlas>(
        AtlasOptionsOf(s), [map_options]() { return std::make_unique<LineEkfMap>(map_options); },
        std::make_shared<LineMapBootstrapper>(map_options));
  }
  const SonarLocalMapOptions sonar = ToSonarMapOptions(s);
  std::shared_ptr<const PoseBootstrapper> w;
  if (s.sensors == RangeSensors::kBoth) w = std::make_shared<LineMapBootstrapper>(map_options);
  if (s.sensors == RangeSensors::kSonar && s.sonar_bootstrap)
    w = std::make_shared<SonarMapBootstrapper>();
  return std::make_unique<Atlas>(
      AtlasOptionsOf(s), [sonar]() { return std::make_unique<SonarLocalMap>(sonar); }, w);
}

Mat3 OdometryIncrementNoise(const Pose2& delta, const MapperSettings& s) {
  return LineEkfMap::OdometryNoise(delta, LocalMapOptionsOf(s).odometry);
}

}  // namespace atlas
