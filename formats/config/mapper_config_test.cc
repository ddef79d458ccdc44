#include "formats/config/mapper_config.h"

#include <gtest/gtest.h>

#include <cmath>
#include <map>
#include <sstream>
#include <string>
#include <type_traits>

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
  EXPECT_DOUBLE_EQ(s.odometry.track_width, 0.5);
  EXPECT_DOUBLE_EQ(s.odometry.wheel_var_per_m, 0.02 * 0.02);
  EXPECT_DOUBLE_EQ(s.odometry.xy_var_per_m, 0.03 * 0.03);
  EXPECT_DOUBLE_EQ(s.odometry.xy_var_per_rad, 0.04 * 0.04);
  EXPECT_DOUBLE_EQ(s.odometry.theta_var_per_m, 0.05 * 0.05);
  EXPECT_DOUBLE_EQ(s.odometry.theta_var_per_rad, 0.06 * 0.06);
  EXPECT_DOUBLE_EQ(s.odometry.wheel_scale_sigma, 0.001);
  EXPECT_DOUBLE_EQ(s.odometry.track_width_sigma, 0.002);
  EXPECT_DOUBLE_EQ(s.laser_range_sigma_m, 0.015);
  EXPECT_DOUBLE_EQ(s.wall_sigma_m, 0.025);
  EXPECT_DOUBLE_EQ(s.line_rho_sigma_min_m, 0.035);
  EXPECT_NEAR(s.line_alpha_sigma_min_rad, 2.0 * M_PI / 180.0, 1e-12);
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

// Every field of the mapper's settings and of the step loop's options, by name, as text
// (%.17g: equal text is an equal double).
std::map<std::string, std::string> Fields(const MapperSettings& s, const StepLoopOptions& l) {
  std::map<std::string, std::string> f;
  auto put = [&f](const std::string& name, auto value) {
    std::ostringstream out;
    out.precision(17);
    if constexpr (std::is_enum_v<decltype(value)>) {
      out << static_cast<int>(value);
    } else {
      out << value;
    }
    f[name] = out.str();
  };
#define ATLAS_PUT(x) put(#x, x)
  ATLAS_PUT(s.map_capacity);
  ATLAS_PUT(s.max_hypotheses);
  ATLAS_PUT(s.probation_steps);
  ATLAS_PUT(s.switch_margin);
  ATLAS_PUT(s.quality_alpha);
  ATLAS_PUT(s.max_sigma_x);
  ATLAS_PUT(s.max_sigma_y);
  ATLAS_PUT(s.max_sigma_theta);
  ATLAS_PUT(s.frames_examined_per_step);
  ATLAS_PUT(s.match_candidates_per_step);
  ATLAS_PUT(s.odometry.track_width);
  ATLAS_PUT(s.odometry.wheel_var_per_m);
  ATLAS_PUT(s.odometry.xy_var_per_m);
  ATLAS_PUT(s.odometry.xy_var_per_rad);
  ATLAS_PUT(s.odometry.theta_var_per_m);
  ATLAS_PUT(s.odometry.theta_var_per_rad);
  ATLAS_PUT(s.odometry.wheel_scale_sigma);
  ATLAS_PUT(s.odometry.track_width_sigma);
  ATLAS_PUT(s.laser_range_sigma_m);
  ATLAS_PUT(s.wall_sigma_m);
  ATLAS_PUT(s.line_rho_sigma_min_m);
  ATLAS_PUT(s.line_alpha_sigma_min_rad);
  ATLAS_PUT(s.sensors);
  ATLAS_PUT(s.sonar_ring.size());
  ATLAS_PUT(s.sonar_bootstrap);
  ATLAS_PUT(s.scan_match.enabled);
  ATLAS_PUT(s.scan_match.min_range);
  ATLAS_PUT(s.scan_match.max_range);
  ATLAS_PUT(s.scan_match.point_sigma);
  ATLAS_PUT(s.scan_match.information_scale);
  ATLAS_PUT(s.scan_match.huber_k);
  ATLAS_PUT(s.scan_match.normal_beams);
  ATLAS_PUT(s.scan_match.normal_radius);
  ATLAS_PUT(s.scan_match.max_normal_rms);
  ATLAS_PUT(s.scan_match.min_normal_extent);
  ATLAS_PUT(s.scan_match.min_point_spacing);
  ATLAS_PUT(s.scan_match.search_beams);
  ATLAS_PUT(s.scan_match.max_distance);
  ATLAS_PUT(s.scan_match.final_distance);
  ATLAS_PUT(s.scan_match.coarse_iterations);
  ATLAS_PUT(s.scan_match.max_iterations);
  ATLAS_PUT(s.scan_match.heading_search);
  ATLAS_PUT(l.step_budget.count());
  ATLAS_PUT(l.max_pending_scans);
  ATLAS_PUT(l.max_range_m);
  ATLAS_PUT(l.laser_timeout.count());
  ATLAS_PUT(l.dead_reckoning_period.count());
  ATLAS_PUT(l.odometry_capacity);
  ATLAS_PUT(l.laser_time_offset.count());
  ATLAS_PUT(l.stamp_resolution.count());
#undef ATLAS_PUT
  return f;
}

// One default per setting: the mapper and the step loop that config/atlasd.toml configures are
// the ones their default-constructed options give, field by field. atlasd without a file, and
// the tools that start from MapperSettings and StepLoopOptions (atlas-replay without --config,
// replay/replay_run.h), therefore map as atlasd does with the shipped file. (That the file sets
// every key to DaemonOptions' default: ConfigLoader.ShippedFileSetsEveryKeyToItsDefault.)
TEST(MapperConfig, ShippedFileGivesTheMappersDefaults) {
  const ConfigResult r =
      LoadConfigFile(ATLAS_SOURCE_DIR "/config/atlasd.toml", ValidateMapperOptions);
  for (const ConfigError& e : r.errors) ADD_FAILURE() << e.ToString();
  ASSERT_TRUE(r.ok());
  const auto shipped = Fields(ToMapperSettings(r.options), ToStepLoopOptions(r.options));
  const auto defaults = Fields(MapperSettings{}, StepLoopOptions{});
  for (const auto& [name, value] : defaults) EXPECT_EQ(shipped.at(name), value) << name;
  EXPECT_EQ(Fields(ToMapperSettings(DaemonOptions{}), ToStepLoopOptions(DaemonOptions{})),
            defaults);
}

}  // namespace
}  // namespace atlas
