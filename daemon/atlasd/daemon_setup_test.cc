#include "daemon/atlasd/daemon_setup.h"

#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <string>
#include <vector>

#include "atlas_paths.h"
#include "formats/config/config_loader.h"
#include "formats/config/config_schema.h"

namespace atlas {
namespace {

// The driver threads are on the pose's latency path: with a real-time loop they run SCHED_FIFO
// at the loop's priority, and at normal priority otherwise.
TEST(DaemonSetup, DriverThreadsFollowTheLoopsRealTimePriority) {
  DaemonOptions o;
  o.scheduling.policy = SchedPolicy::kOther;
  o.scheduling.priority = 0;
  EXPECT_EQ(ToLaserReaderOptions(o).reconnect.realtime_priority, 0);
  EXPECT_EQ(ToOdometryReaderOptions(o).reconnect.realtime_priority, 0);
  EXPECT_EQ(ToSonarReaderOptions(o).reconnect.realtime_priority, 0);
  EXPECT_EQ(ToLcmInputOptions(o).realtime_priority, 0);
  for (SchedPolicy policy : {SchedPolicy::kFifo, SchedPolicy::kRoundRobin}) {
    o.scheduling.policy = policy;
    o.scheduling.priority = 37;
    EXPECT_EQ(ToLaserReaderOptions(o).reconnect.realtime_priority, 37);
    EXPECT_EQ(ToOdometryReaderOptions(o).reconnect.realtime_priority, 37);
    EXPECT_EQ(ToSonarReaderOptions(o).reconnect.realtime_priority, 37);
    EXPECT_EQ(ToLcmInputOptions(o).realtime_priority, 37);
  }
  EXPECT_EQ(ValidateDerivedOptions(o), "");
}

// laser.max_range_m is the scanner's setting: its reader applies it, not the mapper.
TEST(DaemonSetup, LaserReaderTakesTheRangeSetting) {
  DaemonOptions o;
  o.laser.max_range_m = 6.5;
  EXPECT_EQ(ToLaserReaderOptions(o).max_range, 6.5f);
  EXPECT_EQ(ToLaserReaderOptions(o).Validate(), "");
}

// input.source = "lcm": the subscriber gets lcm.url, the [input] keys and what the laser
// messages of libbot do not carry (the mount, the maximum range), and no device is checked.
TEST(DaemonSetup, LcmInputTakesTheInputKeysAndTheLasersMount) {
  DaemonOptions o;
  o.input.source = InputSource::kLcm;
  o.input.laser_type = LaserMessageType::kPlanarLidar;
  o.input.odometry_channel = "POSE";
  o.lcm.url = "udpm://239.255.76.67:7667?ttl=1";
  o.laser.mount = MountPose{0.2, -0.1, 90.0};
  o.laser.max_range_m = 30.0;
  o.laser.queue_capacity = 5;
  o.odometry.queue_capacity = 7;
  const LcmInputOptions i = ToLcmInputOptions(o);
  EXPECT_EQ(i.url, o.lcm.url);
  EXPECT_EQ(i.laser_type, LaserMessageType::kPlanarLidar);
  EXPECT_EQ(i.laser_channel, "ATLAS_RAW_LASER");
  EXPECT_EQ(i.odometry_channel, "POSE");
  EXPECT_EQ(i.laser.sensor_pose.x, 0.2);
  EXPECT_NEAR(i.laser.sensor_pose.theta, M_PI / 2, 1e-12);
  EXPECT_EQ(i.laser.max_range, 30.0f);
  EXPECT_EQ(i.laser_queue_capacity, 5u);
  EXPECT_EQ(i.odometry_queue_capacity, 7u);
  EXPECT_EQ(ValidateDerivedOptions(o), "");
  o.laser.enabled = false;
  EXPECT_FALSE(ToLcmInputOptions(o).laser_enabled);
}

// Every shipped configuration file passes the checks atlasd makes, the device readers' included.
TEST(DaemonSetup, EveryShippedFileIsValid) {
  int files = 0;
  for (const auto& e : std::filesystem::directory_iterator(ATLAS_SOURCE_DIR "/config")) {
    if (e.path().extension() != ".toml") continue;
    ++files;
    const ConfigResult r = LoadConfigFile(e.path().string(), ValidateDerivedOptions);
    for (const ConfigError& err : r.errors) ADD_FAILURE() << err.ToString();
    EXPECT_EQ(r.options.Validate(), "") << e.path();
  }
  EXPECT_GT(files, 0) << "no config/*.toml found";
}

// Sets the n-th end of the schema's ranges (both ends of a range, every allowed value of a list
// or enum, both booleans) and names its key; key stays empty past the last end. Strings keep
// their defaults.
class RangeEnd {
 public:
  explicit RangeEnd(int n) : n_(n) {}
  std::string key;

  template <typename F>
  void Section(const char* name, F body) {
    const std::string saved = prefix_;
    prefix_ += std::string(name) + ".";
    body();
    prefix_ = saved;
  }
  void Bool(const char* k, bool& v) {
    Try(k, v, false);
    Try(k, v, true);
  }
  void Int(const char* k, int& v, int lo, int hi) {
    Try(k, v, lo);
    Try(k, v, hi);
  }
  void IntOneOf(const char* k, int& v, std::initializer_list<int> allowed) {
    for (int a : allowed) Try(k, v, a);
  }
  void Double(const char* k, double& v, double lo, double hi) {
    Try(k, v, lo);
    Try(k, v, hi);
  }
  void DoubleOneOf(const char* k, double& v, std::initializer_list<double> allowed) {
    for (double a : allowed) Try(k, v, a);
  }
  void String(const char*, std::string&, config::StringCheck) {}
  template <typename E, size_t N>
  void Enum(const char* k, E& v, const config::EnumNames<E, N>& names) {
    for (const auto& entry : names) Try(k, v, entry.second);
  }
  void IntList(const char* k, std::vector<int>& v, int lo, int hi, size_t) {
    Try(k, v, std::vector<int>{lo});
    Try(k, v, std::vector<int>{hi});
  }

 private:
  template <typename T, typename U>
  void Try(const char* k, T& v, const U& x) {
    if (i_++ != n_) return;
    v = x;
    key = prefix_ + k;
  }

  int n_;
  int i_ = 0;
  std::string prefix_;
};

// The configuration file's ranges (config_schema.h) lie within what the options derived from
// them accept: a file that --check-config passes does not fail the atlas, local maps, step loop
// or device readers at start-up. Each end of each range, alone, on a laser, a sonar, a
// laser+sonar and an LCM input configuration (the sonar options are checked only with the sonar
// enabled).
TEST(DaemonSetup, EveryEndOfEveryConfigRangePassesTheDerivedOptions) {
  std::vector<DaemonOptions> bases(4);
  bases[3].input.source = InputSource::kLcm;
  bases[1].sonar.enabled = true;
  bases[1].localmap.sensors = RangeSensors::kSonar;
  bases[2].sonar.enabled = true;
  bases[2].localmap.sensors = RangeSensors::kBoth;
  int checked = 0;
  for (const DaemonOptions& base : bases) {
    ASSERT_EQ(ValidateDerivedOptions(base), "");
    for (int n = 0;; ++n) {
      DaemonOptions o = base;
      RangeEnd end(n);
      config::VisitOptions(end, o);
      if (end.key.empty()) break;
      if (!o.Validate().empty()) continue;  // refused by a cross-field rule of the file
      ++checked;
      EXPECT_EQ(ValidateDerivedOptions(o), "")
          << end.key << " = " << FlattenOptions(o).at(end.key) << " passes the schema";
    }
  }
  EXPECT_GT(checked, 4 * 100);
  // What the audit found: the schema allowed 1 for both, the atlas needs 2.
  DaemonOptions o;
  o.atlas.max_hypotheses = 1;
  EXPECT_NE(o.Validate(), "");
  EXPECT_NE(ValidateDerivedOptions(o), "");
  o = DaemonOptions{};
  o.atlas.frames_examined_per_step = 1;
  EXPECT_NE(o.Validate(), "");
  EXPECT_NE(ValidateDerivedOptions(o), "");
}

}  // namespace
}  // namespace atlas
