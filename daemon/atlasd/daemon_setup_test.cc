#include "daemon/atlasd/daemon_setup.h"

#include <gtest/gtest.h>

#include <cmath>
#include <string>
#include <vector>

#include "daemon/config/config_loader.h"
#include "daemon/config/config_schema.h"

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
  for (SchedPolicy policy : {SchedPolicy::kFifo, SchedPolicy::kRoundRobin}) {
    o.scheduling.policy = policy;
    o.scheduling.priority = 37;
    EXPECT_EQ(ToLaserReaderOptions(o).reconnect.realtime_priority, 37);
    EXPECT_EQ(ToOdometryReaderOptions(o).reconnect.realtime_priority, 37);
    EXPECT_EQ(ToSonarReaderOptions(o).reconnect.realtime_priority, 37);
  }
  EXPECT_EQ(ValidateDerivedOptions(o), "");
}

// The configured noise reaches the local maps: sigmas after one unit of motion become the
// model's variances per unit, the line floors reach the extraction.
TEST(DaemonSetup, NoiseModelsReachTheMapper) {
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
TEST(DaemonSetup, LaserTimeOffsetReachesTheLoop) {
  DaemonOptions o;
  EXPECT_EQ(ToStepLoopOptions(o).laser_time_offset, Duration::zero());
  o.laser.time_offset_s = -0.12;
  EXPECT_EQ(ToStepLoopOptions(o).laser_time_offset, std::chrono::milliseconds(-120));
  EXPECT_EQ(ValidateDerivedOptions(o), "");
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
// or device readers at start-up. Each end of each range, alone, on a laser, a sonar and a
// laser+sonar configuration (the sonar options are checked only with the sonar enabled).
TEST(DaemonSetup, EveryEndOfEveryConfigRangePassesTheDerivedOptions) {
  std::vector<DaemonOptions> bases(3);
  bases[1].sonar.enabled = true;
  bases[1].localmap.sensors = LocalMapSensors::kSonar;
  bases[2].sonar.enabled = true;
  bases[2].localmap.sensors = LocalMapSensors::kBoth;
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
  EXPECT_GT(checked, 3 * 100);
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
