#include "formats/config/config_loader.h"

#include <gmock/gmock.h>
#include <gtest/gtest.h>
#include <sys/stat.h>
#include <toml++/toml.h>

#include <cerrno>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <map>
#include <sstream>

#include "atlas_paths.h"
#include "formats/config/mapper_config.h"

namespace atlas {
namespace {

static_assert(kExitConfigError == 78, "sysexits.h EX_CONFIG, what systemd and scripts expect");

using ::testing::HasSubstr;

std::map<std::string, std::string> Dump(const DaemonOptions& o) { return FlattenOptions(o); }

std::vector<std::filesystem::path> ShippedConfigFiles() {
  std::vector<std::filesystem::path> files;
  for (const auto& e : std::filesystem::directory_iterator(ATLAS_SOURCE_DIR "/config")) {
    if (e.path().extension() == ".toml") files.push_back(e.path());
  }
  return files;
}

// The single error of r, which must name key at line.
void ExpectOneError(const ConfigResult& r, const std::string& key, int line,
                    const std::string& message_part) {
  ASSERT_EQ(r.errors.size(), 1u) << (r.errors.empty() ? "" : r.errors[0].ToString());
  EXPECT_EQ(r.errors[0].key, key);
  EXPECT_EQ(r.errors[0].line, line);
  EXPECT_EQ(r.errors[0].file, "test.toml");
  EXPECT_THAT(r.errors[0].message, HasSubstr(message_part));
  EXPECT_THAT(r.errors[0].ToString(), HasSubstr("test.toml:" + std::to_string(line) + ":"));
  EXPECT_THAT(r.errors[0].ToString(), HasSubstr(key));
}

TEST(ConfigLoader, ShippedFileSetsEveryKeyToItsDefault) {
  const std::string path = ATLAS_SOURCE_DIR "/config/atlasd.toml";
  const toml::table root = toml::parse_file(path);
  for (const auto& [key, value] : Dump(DaemonOptions{})) {
    EXPECT_TRUE(root.at_path(key)) << key << " is not in " << path;
  }
  const ConfigResult r = LoadConfigFile(path, ValidateMapperOptions);
  ASSERT_TRUE(r.ok());
  EXPECT_EQ(Dump(r.options), Dump(DaemonOptions{}))
      << "config/atlasd.toml says it shows the defaults of daemon_options.h";
}

// Every key line of a shipped file sits in a block (no blank line) that starts with a comment.
TEST(ConfigLoader, EveryShippedKeyIsCommented) {
  for (const auto& f : ShippedConfigFiles()) {
    std::ifstream in(f);
    std::string line;
    bool block_has_comment = false;
    int n = 0;
    while (std::getline(in, line)) {
      ++n;
      const size_t first = line.find_first_not_of(" \t");
      if (first == std::string::npos) {
        block_has_comment = false;
      } else if (line[first] == '#') {
        block_has_comment = true;
      } else if (line[first] != '[') {
        EXPECT_TRUE(block_has_comment) << f << ":" << n << ": key without a comment: " << line;
      }
    }
  }
}

TEST(ConfigLoader, EmptyFileGivesDefaults) {
  const ConfigResult r = LoadConfigString("", "test.toml");
  EXPECT_TRUE(r.ok());
  EXPECT_EQ(Dump(r.options), Dump(DaemonOptions{}));
}

TEST(ConfigLoader, ReadsValues) {
  const ConfigResult r = LoadConfigString(R"(
[laser]
baud = 38400
angular_range_deg = 100
angular_resolution_deg = 0.25
unit = "cm"
max_range_m = 30
time_offset_s = -0.12
[laser.mount]
theta_deg = 90
[odometry]
interface = "unix:/tmp/fakecan"
track_width_m = 1
[sonar]
enabled = true
ring = "b21_24"
[lcm]
republish_raw = true
[lcm.channels]
pose = "MY_POSE"
[scheduling]
policy = "fifo"
priority = 40
cpu_affinity = [1]
mlockall = true
)",
                                          "test.toml");
  for (const ConfigError& e : r.errors) ADD_FAILURE() << e.ToString();
  const DaemonOptions& o = r.options;
  EXPECT_EQ(o.laser.baud, 38400);
  EXPECT_EQ(o.laser.angular_range_deg, 100);
  EXPECT_DOUBLE_EQ(o.laser.angular_resolution_deg, 0.25);
  EXPECT_EQ(o.laser.unit, sick::Unit::kCentimetre);
  EXPECT_DOUBLE_EQ(o.laser.max_range_m, 30.0);
  EXPECT_DOUBLE_EQ(o.laser.time_offset_s, -0.12);
  EXPECT_DOUBLE_EQ(o.laser.mount.theta_deg, 90.0);
  EXPECT_DOUBLE_EQ(o.laser.mount.x_m, 0.1);  // default kept
  EXPECT_EQ(o.odometry.interface, "unix:/tmp/fakecan");
  EXPECT_DOUBLE_EQ(o.odometry.track_width_m, 1.0);  // an integer where a number is expected
  EXPECT_TRUE(o.sonar.enabled);
  EXPECT_EQ(o.sonar.ring, SonarRing::kB21_24);
  EXPECT_TRUE(o.lcm.republish_raw);
  EXPECT_EQ(o.lcm.channels.pose, "MY_POSE");
  EXPECT_EQ(o.lcm.channels.health, "ATLAS_HEALTH");
  EXPECT_EQ(o.scheduling.policy, SchedPolicy::kFifo);
  EXPECT_EQ(o.scheduling.priority, 40);
  EXPECT_EQ(o.scheduling.cpu_affinity, std::vector<int>{1});
  EXPECT_TRUE(o.scheduling.mlockall);
}

TEST(ConfigLoader, UnknownKeyNamesKeyAndLine) {
  ExpectOneError(LoadConfigString("[laser]\nbaud = 9600\nbuad = 9600\n", "test.toml"), "laser.buad",
                 3, "unknown key");
  ExpectOneError(LoadConfigString("\n\n[lasr]\nbaud = 9600\n", "test.toml"), "lasr", 3,
                 "unknown section");
  ExpectOneError(LoadConfigString("[lcm.channels]\n\nposes = \"X\"\n", "test.toml"),
                 "lcm.channels.poses", 3, "unknown key");
}

TEST(ConfigLoader, WrongTypeNamesKeyAndLine) {
  ExpectOneError(LoadConfigString("[odometry]\n\ntrack_width_m = \"wide\"\n", "test.toml"),
                 "odometry.track_width_m", 3, "expected a number, got a string");
  ExpectOneError(LoadConfigString("[atlas]\nmap_capacity = 2.5\n", "test.toml"),
                 "atlas.map_capacity", 2, "expected an integer");
  ExpectOneError(LoadConfigString("[sonar]\nenabled = 1\n", "test.toml"), "sonar.enabled", 2,
                 "expected a boolean");
  ExpectOneError(LoadConfigString("laser = 3\n", "test.toml"), "laser", 1, "expected a table");
  ExpectOneError(LoadConfigString("[scheduling]\ncpu_affinity = [0, \"1\"]\n", "test.toml"),
                 "scheduling.cpu_affinity[1]", 2, "expected an integer");
}

TEST(ConfigLoader, OutOfRangeNamesKeyAndLine) {
  ExpectOneError(LoadConfigString("[atlas]\nquality_alpha = 1.5\n", "test.toml"),
                 "atlas.quality_alpha", 2, "must be between 0 and 1, got 1.5");
  ExpectOneError(LoadConfigString("[laser]\nbaud = 115200\n", "test.toml"), "laser.baud", 2,
                 "must be one of 9600, 19200, 38400, 500000");
  ExpectOneError(LoadConfigString("[laser]\nunit = \"inch\"\n", "test.toml"), "laser.unit", 2,
                 "must be one of \"cm\", \"mm\"");
  ExpectOneError(LoadConfigString("[laser]\ntime_offset_s = -1.5\n", "test.toml"),
                 "laser.time_offset_s", 2, "must be between -1 and 1, got -1.5");
  ExpectOneError(LoadConfigString("[laser]\ntime_offset_s = \"-0.1\"\n", "test.toml"),
                 "laser.time_offset_s", 2, "expected a number, got a string");
  ExpectOneError(LoadConfigString("[atlas]\nmax_sigma_x = nan\n", "test.toml"), "atlas.max_sigma_x",
                 2, "finite");
  ExpectOneError(LoadConfigString("[odometry]\ninterface = \"can0/x\"\n", "test.toml"),
                 "odometry.interface", 2, "CAN interface name");
  ExpectOneError(LoadConfigString("[state]\ndirectory = \"var/lib\"\n", "test.toml"),
                 "state.directory", 2, "absolute");
  ExpectOneError(LoadConfigString("[atlas]\nmap_capacity = 99999999999\n", "test.toml"),
                 "atlas.map_capacity", 2, "got 99999999999");
}

TEST(ConfigLoader, CrossFieldRulesNameKeyAndLine) {
  ExpectOneError(LoadConfigString("[scheduling]\npolicy = \"fifo\"\npriority = 0\n", "test.toml"),
                 "scheduling.priority", 3, "1..99");
  ExpectOneError(LoadConfigString("[laser]\nangular_resolution_deg = 0.25\n", "test.toml"),
                 "laser.angular_resolution_deg", 2, "angular_range_deg = 100");
  ExpectOneError(LoadConfigString("[lcm.channels]\nraw_laser = \"ATLAS_POSE\"\n", "test.toml"),
                 "lcm.channels.raw_laser", 2, "same channel as lcm.channels.pose");
}

// [input]: devices or LCM, the message types and channels.
TEST(ConfigLoader, InputChoosesDevicesOrLcmWithItsTypesAndChannels) {
  const ConfigResult r = LoadConfigString(
      "[input]\nsource = \"lcm\"\nlaser_type = \"bot_core.planar_lidar_t\"\n"
      "odometry_type = \"bot_core.pose_t\"\nlaser_channel = \"SCAN\"\n"
      "odometry_channel = \"POSE\"\n",
      "test.toml");
  ASSERT_TRUE(r.ok()) << r.errors[0].ToString();
  EXPECT_EQ(r.options.input.source, InputSource::kLcm);
  EXPECT_EQ(r.options.input.laser_type, LaserMessageType::kPlanarLidar);
  EXPECT_EQ(r.options.input.odometry_type, OdometryMessageType::kBotPose);
  EXPECT_EQ(r.options.input.laser_channel, "SCAN");
  EXPECT_EQ(r.options.input.odometry_channel, "POSE");
  EXPECT_EQ(DaemonOptions{}.input.laser_channel, DaemonOptions{}.lcm.channels.raw_laser);
  EXPECT_EQ(DaemonOptions{}.input.odometry_channel, DaemonOptions{}.lcm.channels.raw_odometry);
}

TEST(ConfigLoader, BadInputKeysNameTheKeyAndLine) {
  ExpectOneError(
      LoadConfigString("[input]\nsource = \"lcm\"\nlaser_type = \"planar_lidar_t\"\n", "test.toml"),
      "input.laser_type", 3, "\"laser_scan_t\", \"bot_core.planar_lidar_t\"");
  ExpectOneError(LoadConfigString("[input]\nsource = \"ros\"\n", "test.toml"), "input.source", 2,
                 "\"devices\", \"lcm\"");
  ExpectOneError(LoadConfigString("[input]\nodometry_typ = \"odometry_t\"\n", "test.toml"),
                 "input.odometry_typ", 2, "unknown key");
  ExpectOneError(LoadConfigString("[input]\nlaser_channel = 3\n", "test.toml"),
                 "input.laser_channel", 2, "expected a string");
  ExpectOneError(LoadConfigString("[input]\nlaser_channel = \"A B\"\n", "test.toml"),
                 "input.laser_channel", 2, "without spaces");
}

TEST(ConfigLoader, LcmInputRulesNameTheKeyToChange) {
  ExpectOneError(
      LoadConfigString("[input]\nsource = \"lcm\"\n[sonar]\nenabled = true\n", "test.toml"),
      "sonar.enabled", 4, "reads no sonar");
  ExpectOneError(
      LoadConfigString("[input]\nsource = \"lcm\"\nodometry_channel = \"ATLAS_RAW_LASER\"\n",
                       "test.toml"),
      "input.odometry_channel", 3, "same channel as input.laser_channel");
  // Its own output fed back in.
  const ConfigResult raw =
      LoadConfigString("[input]\nsource = \"lcm\"\n[lcm]\nrepublish_raw = true\n", "test.toml");
  ASSERT_EQ(raw.errors.size(), 2u);
  for (const ConfigError& e : raw.errors) {
    EXPECT_EQ(e.key, "lcm.republish_raw");
    EXPECT_EQ(e.line, 4);
  }
  EXPECT_THAT(raw.errors[0].message, HasSubstr("lcm.channels.raw_laser"));
  EXPECT_THAT(raw.errors[0].message, HasSubstr("which is input.laser_channel"));
  EXPECT_THAT(raw.errors[1].message, HasSubstr("which is input.odometry_channel"));
  ExpectOneError(
      LoadConfigString("[input]\nsource = \"lcm\"\nlaser_channel = \"ATLAS_POSE\"\n", "test.toml"),
      "input.laser_channel", 3, "lcm.channels.pose, which atlasd publishes on");
  // With the devices, the [input] channels are not read.
  EXPECT_TRUE(LoadConfigString("[input]\nlaser_channel = \"ATLAS_POSE\"\n[sonar]\nenabled = true\n",
                               "test.toml")
                  .ok());
}

// localmap.sensors: the local maps run on the laser, the sonar or both.
TEST(ConfigLoader, RangeSensorsChoosesLaserSonarOrBoth) {
  const ConfigResult sonar =
      LoadConfigString("[sonar]\nenabled = true\n[localmap]\nsensors = \"sonar\"\n", "test.toml");
  ASSERT_TRUE(sonar.ok()) << sonar.errors[0].ToString();
  EXPECT_EQ(sonar.options.localmap.sensors, RangeSensors::kSonar);
  const ConfigResult both =
      LoadConfigString("[sonar]\nenabled = true\n[localmap]\nsensors = \"both\"\n", "test.toml");
  ASSERT_TRUE(both.ok()) << both.errors[0].ToString();
  EXPECT_EQ(both.options.localmap.sensors, RangeSensors::kBoth);
  EXPECT_EQ(DaemonOptions{}.localmap.sensors, RangeSensors::kLaser);
  EXPECT_TRUE(DaemonOptions{}.localmap.sonar_bootstrap);
  const ConfigResult without_w = LoadConfigString(
      "[sonar]\nenabled = true\n[localmap]\nsensors = \"sonar\"\nsonar_bootstrap = false\n",
      "test.toml");
  ASSERT_TRUE(without_w.ok());
  EXPECT_FALSE(without_w.options.localmap.sonar_bootstrap);
  // localmap.kind: lines (the default) or grids, with the laser alone.
  EXPECT_EQ(DaemonOptions{}.localmap.kind, LocalMapKind::kLines);
  const ConfigResult grid = LoadConfigString("[localmap]\nkind = \"grid\"\n", "test.toml");
  ASSERT_TRUE(grid.ok()) << grid.errors[0].ToString();
  EXPECT_EQ(grid.options.localmap.kind, LocalMapKind::kGrid);
  ExpectOneError(LoadConfigString("[sonar]\nenabled = true\n[localmap]\nsensors = \"sonar\"\n"
                                  "kind = \"grid\"\n",
                                  "test.toml"),
                 "localmap.kind", 5, "needs sensors = \"laser\"");
  // An unknown value is rejected with the key, the line and the accepted values.
  ExpectOneError(LoadConfigString("\n[localmap]\nsensors = \"radar\"\n", "test.toml"),
                 "localmap.sensors", 3, "must be one of \"laser\", \"sonar\", \"both\"");
  // Mapping with a sensor that is not enabled.
  ExpectOneError(LoadConfigString("[localmap]\nsensors = \"sonar\"\n", "test.toml"),
                 "localmap.sensors", 2, "needs sonar.enabled = true");
  ExpectOneError(LoadConfigString("[laser]\nenabled = false\n[sonar]\nenabled = true\n"
                                  "[localmap]\nsensors = \"both\"\n",
                                  "test.toml"),
                 "localmap.sensors", 6, "needs laser.enabled = true");
  // A change needs a restart (the maps are of another kind).
  DaemonOptions running, loaded;
  loaded.sonar.enabled = true;
  loaded.localmap.sensors = RangeSensors::kSonar;
  EXPECT_THAT(DiffForReload(running, loaded).needs_restart, testing::Contains("localmap.sensors"));
}

TEST(ConfigLoader, CollectsEveryError) {
  const ConfigResult r = LoadConfigString(R"([laser]
baud = 1
[atlas]
quality_alpha = -1
max_hypotheses = "many"
[nonsense]
x = 1
)",
                                          "test.toml");
  ASSERT_EQ(r.errors.size(), 4u);
  std::map<std::string, int> line_of;
  for (const ConfigError& e : r.errors) line_of[e.key] = e.line;
  EXPECT_EQ(line_of["laser.baud"], 2);
  EXPECT_EQ(line_of["atlas.quality_alpha"], 4);
  EXPECT_EQ(line_of["atlas.max_hypotheses"], 5);
  EXPECT_EQ(line_of["nonsense"], 6);
}

// One run lists every problem: the rules between keys and the modules' checks are checked
// beside values out of range, except the rules that read a key whose value was refused.
TEST(ConfigLoader, RulesBetweenKeysAreCheckedInTheRunThatFindsRangeErrors) {
  const ConfigResult r = LoadConfigString(
      "[laser]\nunit = \"mm\"\nmax_range_m = 20\nbaud = 1\n[scheduling]\npolicy = \"other\"\n"
      "priority = 5\n",
      "test.toml");
  std::map<std::string, int> line_of;
  for (const ConfigError& e : r.errors) line_of[e.key] = e.line;
  EXPECT_EQ(r.errors.size(), 3u);
  EXPECT_EQ(line_of["laser.baud"], 4);
  EXPECT_EQ(line_of["laser.max_range_m"], 3);
  EXPECT_EQ(line_of["scheduling.priority"], 7);
  // The unit is refused: the range rule that reads it is not checked against a guess.
  ExpectOneError(LoadConfigString("[laser]\nunit = \"inch\"\nmax_range_m = 20\n", "test.toml"),
                 "laser.unit", 2, "must be one of");
  // A section that is not a table: none of its keys is used by a rule.
  ExpectOneError(
      LoadConfigString("laser = 3\n[sonar]\nenabled = true\n[localmap]\nsensors = \"both\"\n",
                       "test.toml"),
      "laser", 1, "expected a table");
  // The modules' checks too.
  const DerivedCheck odd = [](const DaemonOptions& o) -> std::string {
    return o.atlas.max_hypotheses % 2 != 0 ? "atlas: max_hypotheses must be even\n" : "";
  };
  const ConfigResult d =
      LoadConfigString("[laser]\nbaud = 1\n[atlas]\nmax_hypotheses = 7\n", "test.toml", odd);
  ASSERT_EQ(d.errors.size(), 2u);
  EXPECT_EQ(d.errors[0].key, "laser.baud");
  EXPECT_EQ(d.errors[1].key, "atlas.max_hypotheses");
}

TEST(ConfigLoader, InvalidTomlGivesThePosition) {
  const ConfigResult r = LoadConfigString("[laser]\nbaud = = 3\n", "test.toml");
  ASSERT_EQ(r.errors.size(), 1u);
  EXPECT_EQ(r.errors[0].line, 2);
  EXPECT_THAT(r.errors[0].message, HasSubstr("not valid TOML"));
}

TEST(ConfigLoader, MissingFileIsAnErrorWithTheErrnoText) {
  const ConfigResult r = LoadConfigFile("/nonexistent/atlasd.toml", ValidateMapperOptions);
  ASSERT_EQ(r.errors.size(), 1u);
  EXPECT_THAT(r.errors[0].ToString(), HasSubstr("/nonexistent/atlasd.toml: cannot open"));
  EXPECT_THAT(r.errors[0].message, HasSubstr(std::strerror(ENOENT)));
  EXPECT_THAT(r.errors[0].message, HasSubstr("check the path"));
}

// A directory reads as empty text, which is valid TOML: it must not run on the defaults.
TEST(ConfigLoader, DirectoryIsRefused) {
  const std::string dir = testing::TempDir();
  const ConfigResult r = LoadConfigFile(dir, ValidateMapperOptions);
  ASSERT_EQ(r.errors.size(), 1u);
  EXPECT_EQ(r.errors[0].file, dir);
  EXPECT_THAT(r.errors[0].message, HasSubstr("is a directory, not a configuration file"));
  EXPECT_THAT(r.errors[0].message, HasSubstr("give the path of the TOML file itself"));
  std::ostringstream out, err;
  EXPECT_EQ(CheckConfigCommand(dir, ValidateMapperOptions, out, err), kExitConfigError);
  EXPECT_THAT(err.str(), HasSubstr(dir + ": is a directory"));
  EXPECT_EQ(out.str(), "");
}

// A read that fails (here at once: /proc/self/mem at offset 0 gives EIO) is not an empty file.
TEST(ConfigLoader, ReadErrorIsRefusedWithTheErrnoText) {
  struct stat st;
  ASSERT_EQ(stat("/proc/self/mem", &st), 0);
  ASSERT_TRUE(S_ISREG(st.st_mode));
  const ConfigResult r = LoadConfigFile("/proc/self/mem", ValidateMapperOptions);
  ASSERT_EQ(r.errors.size(), 1u);
  EXPECT_THAT(r.errors[0].message,
              HasSubstr("reading the configuration file failed after 0 bytes"));
  EXPECT_THAT(r.errors[0].message, HasSubstr(std::strerror(EIO)));
}

TEST(ConfigLoader, ValidateChecksProgrammaticOptions) {
  DaemonOptions o;
  EXPECT_EQ(o.Validate(), "");
  o.atlas.max_hypotheses = 0;
  o.lcm.channels.graph = "has space";
  const std::string v = o.Validate();
  EXPECT_THAT(v, HasSubstr("atlas.max_hypotheses: must be between 2 and 64, got 0"));
  EXPECT_THAT(v, HasSubstr("lcm.channels.graph: must be printable ASCII"));
}

TEST(ConfigLoader, FlattenOptionsWritesFileSyntax) {
  DaemonOptions o;
  o.scheduling.cpu_affinity = {0, 1};
  const auto flat = FlattenOptions(o);
  EXPECT_EQ(flat.at("laser.baud"), "500000");
  EXPECT_EQ(flat.at("laser.unit"), "\"mm\"");
  EXPECT_EQ(flat.at("lcm.channels.pose"), "\"ATLAS_POSE\"");
  EXPECT_EQ(flat.at("scheduling.cpu_affinity"), "[0, 1]");
  EXPECT_EQ(flat.at("sonar.enabled"), "false");
  // One flattened key per key of the shipped file, which shows every key.
  size_t shipped_keys = 0;
  const auto count = [&shipped_keys](const toml::table& t, const auto& self) -> void {
    for (const auto& [k, v] : t) {
      if (const toml::table* sub = v.as_table()) {
        self(*sub, self);
      } else {
        ++shipped_keys;
      }
    }
  };
  count(toml::parse_file(ATLAS_SOURCE_DIR "/config/atlasd.toml"), count);
  EXPECT_EQ(flat.size(), shipped_keys) << "a key was added or removed: update config/atlasd.toml";
}

TEST(ConfigLoader, DiffForReloadSeparatesWhatNeedsARestart) {
  DaemonOptions running;
  DaemonOptions loaded;
  loaded.atlas.quality_alpha = 0.7;
  loaded.lcm.republish_raw = true;
  loaded.laser.baud = 38400;
  loaded.state.directory = "/srv/atlas";
  const ReloadDiff d = DiffForReload(running, loaded);
  EXPECT_EQ(d.reloadable, (std::vector<std::string>{"atlas.quality_alpha", "lcm.republish_raw"}));
  EXPECT_EQ(d.needs_restart, (std::vector<std::string>{"laser.baud", "state.directory"}));
  EXPECT_TRUE(DiffForReload(running, running).reloadable.empty());
}

TEST(ConfigLoader, CheckConfigCommandExits78AndNamesTheKey) {
  const std::filesystem::path dir = std::filesystem::path(testing::TempDir());
  const std::string bad = (dir / "atlas_bad_config.toml").string();
  std::ofstream(bad) << "[loop]\nstep_budget_ms = 0\n";
  std::ostringstream out, err;
  EXPECT_EQ(CheckConfigCommand(bad, ValidateMapperOptions, out, err), kExitConfigError);
  EXPECT_THAT(err.str(), HasSubstr(bad + ":2:18: loop.step_budget_ms: must be between 0.1"));
  std::ostringstream out2, err2;
  EXPECT_EQ(
      CheckConfigCommand(ATLAS_SOURCE_DIR "/config/atlasd.toml", ValidateMapperOptions, out2, err2),
      0);
  EXPECT_THAT(out2.str(), HasSubstr("configuration is valid"));
  std::filesystem::remove(bad);
}

// The audit's file: atlas.max_hypotheses = 1 passed --check-config, and atlasd then exited 78
// with "atlas: atlas: max_hypotheses must lie in [2, 64]" and neither file, line nor key.
TEST(ConfigLoader, TooFewHypothesesOrFramesAreRefusedAtTheirKey) {
  const std::filesystem::path dir = std::filesystem::path(testing::TempDir());
  const std::string bad = (dir / "atlas_one_hypothesis.toml").string();
  for (const std::string key : {"max_hypotheses", "frames_examined_per_step"}) {
    std::ofstream(bad) << "[atlas]\nprobation_steps = 20\n" << key << " = 1\n";
    const ConfigResult r = LoadConfigFile(bad, ValidateMapperOptions);
    ASSERT_EQ(r.errors.size(), 1u) << key;
    EXPECT_EQ(r.errors[0].file, bad);
    EXPECT_EQ(r.errors[0].line, 3);
    EXPECT_EQ(r.errors[0].key, "atlas." + key);
    EXPECT_THAT(r.errors[0].message, HasSubstr("must be between 2 and "));
    std::ostringstream out, err;
    EXPECT_EQ(CheckConfigCommand(bad, ValidateMapperOptions, out, err), kExitConfigError);
    EXPECT_THAT(err.str(), HasSubstr(bad + ":3:" + std::to_string(key.size() + 4) + ": atlas." +
                                     key + ": must be between 2 and "));
    EXPECT_EQ(out.str(), "");
    // The lowest value the file allows is one the atlas accepts.
    std::ofstream(bad) << "[atlas]\n" << key << " = 2\n";
    std::ostringstream out2, err2;
    EXPECT_EQ(CheckConfigCommand(bad, ValidateMapperOptions, out2, err2), 0) << err2.str();
  }
  std::filesystem::remove(bad);
}

// What the modules refuse although the file's ranges allow it (a stand-in check here: odd
// hypothesis counts, or both counts 7) is named at the keys that cause it, with their line.
TEST(ConfigLoader, DerivedProblemsAreNamedAtTheKeysThatCauseThem) {
  const DerivedCheck odd = [](const DaemonOptions& o) -> std::string {
    return o.atlas.max_hypotheses % 2 != 0 ? "atlas: max_hypotheses must be even\n" : "";
  };
  const std::string text = "[laser]\nbaud = 38400\n[atlas]\nmap_capacity = 7\nmax_hypotheses = 7\n";
  ExpectOneError(LoadConfigString(text, "test.toml", odd), "atlas.max_hypotheses", 5,
                 "refused by the module it configures (atlas: max_hypotheses must be even)");
  EXPECT_TRUE(LoadConfigString(text, "test.toml").ok()) << "no derived check: the file's rules";
  const DerivedCheck both = [](const DaemonOptions& o) -> std::string {
    return o.atlas.max_hypotheses == o.atlas.map_capacity ? "atlas: both 7\n" : "";
  };
  const ConfigResult r = LoadConfigString(text, "test.toml", both);
  ASSERT_EQ(r.errors.size(), 2u);
  EXPECT_EQ(r.errors[0].ToString(),
            "test.toml:4:16: atlas.map_capacity: refused by the module it configures (atlas: both "
            "7); choose another value (config/atlasd.toml gives each key's range)");
  EXPECT_EQ(r.errors[1].key, "atlas.max_hypotheses");
  EXPECT_EQ(r.errors[1].line, 5);
  // A problem no key of the file causes is reported for the file.
  const DerivedCheck always = [](const DaemonOptions&) -> std::string { return "loop: broken\n"; };
  const ConfigResult f = LoadConfigString(text, "test.toml", always);
  ASSERT_EQ(f.errors.size(), 1u);
  EXPECT_EQ(f.errors[0].line, 0);
  EXPECT_EQ(f.errors[0].key, "");
  EXPECT_THAT(f.errors[0].ToString(), HasSubstr("test.toml: refused by the modules it configures "
                                                "(loop: broken); no single key"));
}

}  // namespace
}  // namespace atlas
