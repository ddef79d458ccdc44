#include "formats/config/mapper_config.h"

#include <gtest/gtest.h>

#include <cmath>
#include <string>

#include "atlas_paths.h"
#include "formats/config/config_loader.h"

namespace atlas {
namespace {

// The configured noise reaches the local maps: sigmas after one unit of motion become the
// model's variances per unit, the line floors reach the extraction.
TEST(MapperConfig, NoiseModelsReachTheMapper) {
  DaemonOptions o;
  o.odometry.track_width_m = 0.5;
  o.noise.odometry.wheel_sigma_per_m = 0.02;
  o.noise.odometry.translation_sigma_per_m = 0.03;
  o.noise.odometry.translation_sigma_per_rad = 0.04;
  o.noise.odometry.rotation_sigma_per_m = 0.05;
  o.noise.odometry.rotation_sigma_per_rad = 0.06;
  o.noise.odometry.wheel_scale_sigma = 0.001;
  o.noise.odometry.track_width_sigma = 0.002;
  o.noise.laser.range_sigma_m = 0.015;
  o.noise.laser.wall_sigma_m = 0.025;
  o.noise.laser.line_rho_sigma_min_m = 0.035;
  o.noise.laser.line_alpha_sigma_min_deg = 2.0;
  const MapperSettings s = ToMapperSettings(o);
  EXPECT_DOUBLE_EQ(s.local_map.odometry.track_width, 0.5);
  EXPECT_DOUBLE_EQ(s.local_map.odometry.wheel_var_per_m, 0.02 * 0.02);
  EXPECT_DOUBLE_EQ(s.local_map.odometry.xy_var_per_m, 0.03 * 0.03);
  EXPECT_DOUBLE_EQ(s.local_map.odometry.xy_var_per_rad, 0.04 * 0.04);
  EXPECT_DOUBLE_EQ(s.local_map.odometry.theta_var_per_m, 0.05 * 0.05);
  EXPECT_DOUBLE_EQ(s.local_map.odometry.theta_var_per_rad, 0.06 * 0.06);
  EXPECT_DOUBLE_EQ(s.local_map.odometry.wheel_scale_sigma, 0.001);
  EXPECT_DOUBLE_EQ(s.local_map.odometry.track_width_sigma, 0.002);
  EXPECT_DOUBLE_EQ(s.local_map.extraction.range_sigma, 0.015);
  EXPECT_DOUBLE_EQ(s.local_map.extraction.model_sigma, 0.025);
  EXPECT_DOUBLE_EQ(s.local_map.extraction.min_rho_sigma, 0.035);
  EXPECT_NEAR(s.local_map.extraction.min_alpha_sigma, 2.0 * M_PI / 180.0, 1e-12);
  EXPECT_EQ(ValidateMapperSettings(s), "");
  // A larger rotation noise gives a larger heading variance for the same increment.
  const Pose2 step{0.5, 0.0, 0.3};
  const double before = OdometryIncrementNoise(step, s)(2, 2);
  o.noise.odometry.rotation_sigma_per_rad = 0.2;
  EXPECT_GT(OdometryIncrementNoise(step, ToMapperSettings(o))(2, 2), before);
}

// laser.time_offset_s reaches the step loop (seconds -> Duration, sign kept).
TEST(MapperConfig, LaserTimeOffsetReachesTheLoop) {
  DaemonOptions o;
  EXPECT_EQ(ToStepLoopOptions(o).laser_time_offset, Duration::zero());
  o.laser.time_offset_s = -0.12;
  EXPECT_EQ(ToStepLoopOptions(o).laser_time_offset, std::chrono::milliseconds(-120));
  EXPECT_EQ(ValidateMapperOptions(o), "");
}

// One default per setting: the mapper and the step loop that config/atlasd.toml configures are
// those of atlasd without a file (DaemonOptions' defaults), of MapperSettings' and
// StepLoopOptions' defaults (atlas-replay without --config: replay/replay_run.h), and of the
// core modules' own defaults, field by field (the options' operator==). (That the file sets
// every key to DaemonOptions' default: ConfigLoader.ShippedFileSetsEveryKeyToItsDefault.)
TEST(MapperConfig, ShippedFileGivesTheMappersDefaults) {
  const ConfigResult r =
      LoadConfigFile(ATLAS_SOURCE_DIR "/config/atlasd.toml", ValidateMapperOptions);
  for (const ConfigError& e : r.errors) ADD_FAILURE() << e.ToString();
  ASSERT_TRUE(r.ok());
  const MapperSettings shipped = ToMapperSettings(r.options);
  const StepLoopOptions shipped_loop = ToStepLoopOptions(r.options);
  for (const MapperSettings& s : {MapperSettings{}, ToMapperSettings(DaemonOptions{})}) {
    EXPECT_TRUE(AtlasOptionsOf(s) == AtlasOptionsOf(shipped));
    EXPECT_TRUE(LocalMapOptionsOf(s) == LocalMapOptionsOf(shipped));
    EXPECT_TRUE(s.scan_match == shipped.scan_match);
    EXPECT_EQ(s.sensors, shipped.sensors);
    EXPECT_EQ(s.sonar_ring.size(), shipped.sonar_ring.size());
    EXPECT_EQ(s.sonar_bootstrap, shipped.sonar_bootstrap);
    EXPECT_EQ(s.grid_frames, shipped.grid_frames);
  }
  EXPECT_TRUE(ToStepLoopOptions(DaemonOptions{}) == shipped_loop);
  EXPECT_TRUE(StepLoopOptions{} == shipped_loop);
  // The laser atlas and its line maps are the core modules' defaults: the factory fixes nothing
  // of its own for them.
  EXPECT_TRUE(AtlasOptionsOf(shipped) == AtlasOptions{});
  EXPECT_TRUE(LocalMapOptionsOf(shipped) == LocalMapOptions{});
  EXPECT_TRUE(shipped.scan_match == ScanMatchOptions{});
}

}  // namespace
}  // namespace atlas
