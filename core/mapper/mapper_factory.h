#pragma once
// Builds the Atlas that atlasd steps: local maps behind the Atlas framework (core/atlas). With
// the laser alone (MapperSettings::sensors) they are line-EKF maps (core/localmap), with w
// (eq. 12) bound by LineMapBootstrapper; with the sonar ring alone or with both they are
// SonarLocalMaps (core/sonar: the same EKF, fed by Atlas::Step with SonarReadings too), w from
// the laser scans when there is a laser; for sonar alone the sonar w (SonarMapBootstrapper,
// core/sonar/sonar_map_bootstrapper.h) unless MapperSettings::sonar_bootstrap is off (then
// juveniles keep their seeded pose and are judged on q alone: docs/design.md, "III-E. Traversal").
// With sonar alone, map-matching uses SonarMapMatchOptions, with laser lines LaserMapMatchOptions
// (core/atlas/map_match.h says what each setting refused, and where it was measured).
//
// MapperSettings is the mapper's part of atlasd's configuration, in the mapper's units (the
// odometry noise as variances, angles in radians): the config (DaemonOptions) converts its keys
// onto it, and the replay tools build the same mapper from it. Its defaults are the defaults of
// config/atlasd.toml, so that every entry point maps alike without a configuration file (a test
// compares them). Settings the file does not name keep the core modules' defaults.

#include <cmath>
#include <memory>
#include <string>
#include <vector>

#include "core/atlas/atlas.h"
#include "core/localmap/localmap_options.h"
#include "core/scanmatch/scan_matcher.h"
#include "core/sonar/sonar_options.h"

namespace atlas {

struct MapperSettings {
  // [atlas]: the Atlas framework's parameters (paper, Sections I-A and III).
  int map_capacity = 10;
  int max_hypotheses = 8;
  int probation_steps = 20;
  double switch_margin = 0.0;  // LifecycleOptions::switch_margin
  double quality_alpha = 0.5;
  double max_sigma_x = 1.0;
  double max_sigma_y = 1.0;
  double max_sigma_theta = 0.35;
  int frames_examined_per_step = 24;
  int match_candidates_per_step = 2;
  // The local maps' noise models (core/localmap/localmap_options.h): wheel odometry
  // ([noise.odometry], variances: the squares of the file's sigmas; the track width is
  // odometry.track_width_m), and the laser's range noise and line-fit floors ([noise.laser]).
  OdometryNoiseOptions odometry{.track_width = 0.58,
                                .wheel_var_per_m = 0.01 * 0.01,
                                .xy_var_per_m = 0.0316 * 0.0316,
                                .xy_var_per_rad = 0.01 * 0.01,
                                .theta_var_per_m = 0.0707 * 0.0707,
                                .theta_var_per_rad = 0.173 * 0.173,
                                .wheel_scale_sigma = 0.0,
                                .track_width_sigma = 0.0};
  double laser_range_sigma_m = 0.01;
  double wall_sigma_m = 0.03;                               // ExtractionOptions::model_sigma
  double line_rho_sigma_min_m = 0.03;                       // ExtractionOptions::min_rho_sigma
  double line_alpha_sigma_min_rad = 1.15 * (M_PI / 180.0);  // ExtractionOptions::min_alpha_sigma
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

// Empty when the settings give valid atlas and local-map options, else the first problem.
std::string ValidateMapperSettings(const MapperSettings& s);

// A new, empty atlas; settings must be valid.
std::unique_ptr<Atlas> MakeAtlas(const MapperSettings& s);

// Covariance of an odometry increment under the local maps' odometry noise model (the same
// Q(u) the maps' Predict uses): for dead reckoning while the laser is away.
Mat3 OdometryIncrementNoise(const Pose2& delta, const MapperSettings& s);

}  // namespace atlas
