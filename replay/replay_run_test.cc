#include "replay/replay_run.h"

#include <gtest/gtest.h>

#include <limits>

#include "atlas_paths.h"
#include "formats/config/config_loader.h"
#include "formats/config/mapper_config.h"

namespace atlas::replay {
namespace {

// atlas-replay without --config (and without options) maps as atlasd with config/atlasd.toml:
// ReplayOptions' mapper and step loop are the ones the shipped file configures, field by field.
TEST(ReplayOptions, DefaultsAreTheShippedFile) {
  const ConfigResult r =
      LoadConfigFile(ATLAS_SOURCE_DIR "/config/atlasd.toml", ValidateMapperOptions);
  for (const ConfigError& e : r.errors) ADD_FAILURE() << e.ToString();
  ASSERT_TRUE(r.ok());
  const MapperSettings shipped = ToMapperSettings(r.options);
  const ReplayOptions defaults;
  EXPECT_EQ(defaults.Validate(), "");
  EXPECT_TRUE(AtlasOptionsOf(defaults.mapper) == AtlasOptionsOf(shipped));
  EXPECT_TRUE(LocalMapOptionsOf(defaults.mapper) == LocalMapOptionsOf(shipped));
  EXPECT_TRUE(defaults.mapper.scan_match == shipped.scan_match);
  EXPECT_EQ(defaults.mapper.sensors, shipped.sensors);
  EXPECT_EQ(defaults.mapper.grid_frames, shipped.grid_frames);
  EXPECT_TRUE(defaults.loop == ToStepLoopOptions(r.options));
  // The scanner's range setting (laser.max_range_m) is the device's: a replay keeps the log's.
  EXPECT_EQ(defaults.laser_max_range, 0.0);
}

TEST(ReplayOptions, LaserRangeSettingIsValidated) {
  ReplayOptions o;
  o.laser_max_range = 8.0;
  EXPECT_EQ(o.Validate(), "");
  for (double bad : {-1.0, std::numeric_limits<double>::quiet_NaN()}) {
    o.laser_max_range = bad;
    EXPECT_NE(o.Validate().find("laser_max_range"), std::string::npos) << bad;
  }
}

}  // namespace
}  // namespace atlas::replay
