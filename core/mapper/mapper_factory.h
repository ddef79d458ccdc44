#pragma once
// Builds the Atlas that atlasd steps: local maps behind the Atlas framework (core/atlas). With
// the laser alone (MapperSettings::sensors) they are line-EKF maps (core/localmap), with w
// (eq. 12) bound by LineMapBootstrapper; with the sonar ring alone or with both they are
// SonarLocalMaps (core/sonar: the same EKF, fed by Atlas::Step with SonarReadings too), w from
// the laser scans when there is a laser; for sonar alone the sonar w (SonarMapBootstrapper,
// core/sonar/sonar_map_bootstrapper.h) unless MapperSettings::sonar_bootstrap is off (then
// juveniles keep their seeded pose and are judged on q alone: docs/design.md, "III-E. Traversal").
// With sonar alone the atlas is SonarAtlasOptions (core/atlas/atlas.h: SonarMapMatchOptions, no
// points, no return band); with laser lines it is AtlasOptions' defaults (LaserMapMatchOptions;
// core/atlas/map_match.h says what each setting refused, and where it was measured).
//
// MapperSettings is the mapper's part of atlasd's configuration: the core modules' options
// (AtlasOptions, LocalMapOptions, ScanMatchOptions) with their defaults, and which sensors the
// maps use. The config (DaemonOptions) converts its keys onto it, and the replay tools build the
// same mapper from it. The core modules' defaults are those of config/atlasd.toml, so every
// entry point maps alike without a configuration file (a test compares them).

#include <memory>
#include <string>
#include <vector>

#include "core/atlas/atlas.h"
#include "core/localmap/localmap_options.h"
#include "core/scanmatch/scan_matcher.h"
#include "core/sonar/sonar_options.h"

namespace atlas {

struct MapperSettings {
  // The atlas (paper, Sections I-A and III), for maps of laser lines; with the sonar alone the
  // factory makes it SonarAtlasOptions(atlas), and with grid frames it turns the points off.
  // The juveniles' probation is at least lifecycle.bootstrap_scans + 1 scans, and with the
  // sonar w at least kSonarBootstrapProbation (core/sonar/sonar_map_bootstrapper.h).
  AtlasOptions atlas;
  // The line local maps (core/localmap): map capacity, odometry and laser noise models. Their
  // quality metric is the atlas's (atlas.quality: alpha and the sigmas of eq. 5).
  LocalMapOptions local_map;
  // The range sensors the maps use, and the sonar ring's geometry (index = transducer) when
  // they use the sonar; the sonar model keeps core/sonar's defaults.
  RangeSensors sensors = RangeSensors::kLaser;
  std::vector<SonarTransducer> sonar_ring;
  // Sonar alone: w (eq. 12) from the sonar readings (SonarMapBootstrapper). On by default: with the
  // sonar extent gap of 1.5 m, w gives fewer false loop closures and a consistent robot pose
  // more often than without it (docs/design.md, "Sonar local maps").
  bool sonar_bootstrap = true;
  // With the laser alone: map-frames hold probability grids (core/gridmap/grid_local_map.h)
  // instead of line EKF maps; core/gridmap's defaults with the odometry noise above.
  bool grid_frames = false;
  // Scan-to-scan matching before each laser step (StepLoop; on by default).
  ScanMatchOptions scan_match;
};

// The options the factory gives the atlas and the line local maps (also inside the sonar and
// grid maps): `s`'s, with what the sensors imply (see MapperSettings).
AtlasOptions AtlasOptionsOf(const MapperSettings& s);
LocalMapOptions LocalMapOptionsOf(const MapperSettings& s);

// Empty when the settings give valid atlas and local-map options, else the first problem.
std::string ValidateMapperSettings(const MapperSettings& s);

// A new, empty atlas; settings must be valid.
std::unique_ptr<Atlas> MakeAtlas(const MapperSettings& s);

// Covariance of an odometry increment under the local maps' odometry noise model (the same
// Q(u) the maps' Predict uses): for dead reckoning while the laser is away.
Mat3 OdometryIncrementNoise(const Pose2& delta, const MapperSettings& s);

}  // namespace atlas
