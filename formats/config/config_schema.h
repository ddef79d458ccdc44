#pragma once
// The one list of atlasd's configuration keys: name, type, range. Both the TOML loader and
// DaemonOptions::Validate() walk it with a visitor, so a key's range is stated once.
//
// A visitor V provides:
//   void Section(const char* name, F body);               // nested table; body() visits it
//   void Bool(const char* key, bool& v);
//   void Int(const char* key, int& v, int lo, int hi);
//   void IntOneOf(const char* key, int& v, std::initializer_list<int> allowed);
//   void Double(const char* key, double& v, double lo, double hi);
//   void DoubleOneOf(const char* key, double& v, std::initializer_list<double> allowed);
//   void String(const char* key, std::string& v, StringCheck check);
//   template <typename E, size_t N> void Enum(const char* key, E& v, const EnumNames<E, N>&);
//   void IntList(const char* key, std::vector<int>& v, int lo, int hi, size_t max_size);
// Cross-field rules (that need two keys) are in CrossCheck().

#include <array>
#include <functional>
#include <string>
#include <utility>

#include "formats/config/daemon_options.h"

namespace atlas::config {

// Returns an empty string when the value is acceptable, else what is wrong with it.
using StringCheck = std::string (*)(const std::string&);

template <typename E, size_t N>
using EnumNames = std::array<std::pair<const char*, E>, N>;

inline constexpr EnumNames<InputSource, 2> kInputSourceNames{
    {{"devices", InputSource::kDevices}, {"lcm", InputSource::kLcm}}};
inline constexpr EnumNames<LaserMessageType, 2> kLaserMessageTypeNames{
    {{"laser_scan_t", LaserMessageType::kLaserScan},
     {"bot_core.planar_lidar_t", LaserMessageType::kPlanarLidar}}};
inline constexpr EnumNames<OdometryMessageType, 2> kOdometryMessageTypeNames{
    {{"odometry_t", OdometryMessageType::kOdometry},
     {"bot_core.pose_t", OdometryMessageType::kBotPose}}};

inline constexpr EnumNames<sick::Unit, 2> kLaserUnitNames{
    {{"cm", sick::Unit::kCentimetre}, {"mm", sick::Unit::kMillimetre}}};
inline constexpr EnumNames<SonarRing, 2> kSonarRingNames{
    {{"p3dx16", SonarRing::kP3dx16}, {"b21_24", SonarRing::kB21_24}}};
inline constexpr EnumNames<RangeSensors, 3> kRangeSensorsNames{{{"laser", RangeSensors::kLaser},
                                                                {"sonar", RangeSensors::kSonar},
                                                                {"both", RangeSensors::kBoth}}};
inline constexpr EnumNames<LocalMapKind, 2> kLocalMapKindNames{
    {{"lines", LocalMapKind::kLines}, {"grid", LocalMapKind::kGrid}}};
inline constexpr EnumNames<SchedPolicy, 3> kSchedPolicyNames{{{"other", SchedPolicy::kOther},
                                                              {"fifo", SchedPolicy::kFifo},
                                                              {"rr", SchedPolicy::kRoundRobin}}};

std::string CheckNonEmpty(const std::string& s);
std::string CheckDevicePath(const std::string& s);
std::string CheckCanInterface(const std::string& s);
std::string CheckLcmUrl(const std::string& s);
std::string CheckChannelName(const std::string& s);
std::string CheckAbsolutePath(const std::string& s);

template <typename V>
void VisitMount(V& v, MountPose& m) {
  v.Double("x_m", m.x_m, -10.0, 10.0);
  v.Double("y_m", m.y_m, -10.0, 10.0);
  v.Double("theta_deg", m.theta_deg, -180.0, 180.0);
}

// A range here must lie within what the options it feeds accept (core/atlas AtlasOptions,
// core/localmap LocalMapOptions, core/sonar, core/scanmatch, the device readers: their
// Validate()); e.g. atlas.max_hypotheses and atlas.frames_examined_per_step (projection_max_frames)
// need at least 2. daemon/atlasd/daemon_setup_test.cc checks both ends of every range.
template <typename V>
void VisitOptions(V& v, DaemonOptions& o) {
  v.Section("input", [&] {
    InputOptions& i = o.input;
    v.Enum("source", i.source, kInputSourceNames);
    v.Enum("laser_type", i.laser_type, kLaserMessageTypeNames);
    v.Enum("odometry_type", i.odometry_type, kOdometryMessageTypeNames);
    v.String("laser_channel", i.laser_channel, CheckChannelName);
    v.String("odometry_channel", i.odometry_channel, CheckChannelName);
  });
  v.Section("laser", [&] {
    LaserOptions& l = o.laser;
    v.Bool("enabled", l.enabled);
    v.String("device", l.device, CheckDevicePath);
    v.IntOneOf("baud", l.baud, {9600, 19200, 38400, 500000});
    v.IntOneOf("angular_range_deg", l.angular_range_deg, {100, 180});
    v.DoubleOneOf("angular_resolution_deg", l.angular_resolution_deg, {1.0, 0.5, 0.25});
    v.Enum("unit", l.unit, kLaserUnitNames);
    v.Double("max_range_m", l.max_range_m, 0.5, 81.91);
    v.Int("queue_capacity", l.queue_capacity, 1, 1024);
    v.Double("time_offset_s", l.time_offset_s, -1.0, 1.0);
    v.Section("mount", [&] { VisitMount(v, l.mount); });
  });
  v.Section("odometry", [&] {
    OdometryOptions& d = o.odometry;
    v.String("interface", d.interface, CheckCanInterface);
    v.Double("track_width_m", d.track_width_m, 0.05, 5.0);
    v.Double("max_speed_mps", d.max_speed_mps, 0.1, 100.0);
    v.Double("slack_m", d.slack_m, 0.0, 10.0);
    v.Double("max_gap_s", d.max_gap_s, 0.02, 10.0);
    v.Int("queue_capacity", d.queue_capacity, 1, 4096);
  });
  v.Section("sonar", [&] {
    SonarOptions& s = o.sonar;
    v.Bool("enabled", s.enabled);
    v.String("device", s.device, CheckDevicePath);
    v.IntOneOf("baud", s.baud, {9600, 19200, 38400, 57600, 115200});
    v.Enum("ring", s.ring, kSonarRingNames);
    v.Double("range_factor_mm", s.range_factor_mm, 0.01, 100.0);
    v.Int("queue_capacity", s.queue_capacity, 1, 1024);
  });
  v.Section("noise", [&] {
    v.Section("odometry", [&] {
      OdometryErrorConfig& n = o.noise.odometry;
      v.Double("wheel_sigma_per_m", n.wheel_sigma_per_m, 0.0, 1.0);
      v.Double("translation_sigma_per_m", n.translation_sigma_per_m, 0.0, 1.0);
      v.Double("translation_sigma_per_rad", n.translation_sigma_per_rad, 0.0, 1.0);
      v.Double("rotation_sigma_per_m", n.rotation_sigma_per_m, 0.0, 1.0);
      v.Double("rotation_sigma_per_rad", n.rotation_sigma_per_rad, 0.0, 1.0);
      v.Double("wheel_scale_sigma", n.wheel_scale_sigma, 0.0, 0.5);
      v.Double("track_width_sigma", n.track_width_sigma, 0.0, 0.5);
    });
    v.Section("laser", [&] {
      LaserNoiseOptions& n = o.noise.laser;
      v.Double("range_sigma_m", n.range_sigma_m, 0.001, 1.0);
      v.Double("wall_sigma_m", n.wall_sigma_m, 0.0, 1.0);
      v.Double("line_rho_sigma_min_m", n.line_rho_sigma_min_m, 0.0, 1.0);
      v.Double("line_alpha_sigma_min_deg", n.line_alpha_sigma_min_deg, 0.0, 30.0);
    });
  });
  v.Section("localmap", [&] {
    v.Enum("sensors", o.localmap.sensors, kRangeSensorsNames);
    v.Enum("kind", o.localmap.kind, kLocalMapKindNames);
    v.Bool("sonar_bootstrap", o.localmap.sonar_bootstrap);
  });
  v.Section("scan_match", [&] {
    ScanMatchConfig& m = o.scan_match;
    v.Bool("enabled", m.enabled);
    v.Double("max_range_m", m.max_range_m, 0.5, 81.91);
    v.Double("point_sigma_m", m.point_sigma_m, 0.001, 1.0);
    v.Double("information_scale", m.information_scale, 0.001, 1.0);
    v.Double("heading_search_deg", m.heading_search_deg, 0.0, 45.0);
  });
  v.Section("atlas", [&] {
    AtlasParameters& a = o.atlas;
    v.Int("map_capacity", a.map_capacity, 1, 1000);
    v.Int("max_hypotheses", a.max_hypotheses, 2, 64);
    v.Int("probation_steps", a.probation_steps, 1, 100000);
    v.Double("switch_margin", a.switch_margin, 0.0, 1.0);
    v.Double("quality_alpha", a.quality_alpha, 0.0, 1.0);
    v.Double("max_sigma_x", a.max_sigma_x, 0.001, 100.0);
    v.Double("max_sigma_y", a.max_sigma_y, 0.001, 100.0);
    v.Double("max_sigma_theta", a.max_sigma_theta, 0.0001, 3.15);
    v.Int("frames_examined_per_step", a.frames_examined_per_step, 2, 1000);
    v.Int("match_candidates_per_step", a.match_candidates_per_step, 1, 1000);
  });
  v.Section("lcm", [&] {
    LcmOptions& l = o.lcm;
    v.String("url", l.url, CheckLcmUrl);
    v.Bool("republish_raw", l.republish_raw);
    v.Double("health_period_s", l.health_period_s, 0.1, 60.0);
    v.Double("graph_period_s", l.graph_period_s, 0.05, 600.0);
    v.Double("local_map_period_s", l.local_map_period_s, 0.0, 600.0);
    v.Int("reference_frame", l.reference_frame, 0, 100000000);
    v.Section("channels", [&] {
      LcmChannels& c = l.channels;
      v.String("pose", c.pose, CheckChannelName);
      v.String("reference_pose", c.reference_pose, CheckChannelName);
      v.String("local_map", c.local_map, CheckChannelName);
      v.String("graph", c.graph, CheckChannelName);
      v.String("hypotheses", c.hypotheses, CheckChannelName);
      v.String("health", c.health, CheckChannelName);
      v.String("raw_odometry", c.raw_odometry, CheckChannelName);
      v.String("raw_laser", c.raw_laser, CheckChannelName);
      v.String("raw_sonar", c.raw_sonar, CheckChannelName);
    });
  });
  v.Section("loop", [&] {
    v.Double("step_budget_ms", o.loop.step_budget_ms, 0.1, 1000.0);
    v.Int("max_pending_scans", o.loop.max_pending_scans, 1, 64);
  });
  v.Section("state", [&] {
    v.String("directory", o.state.directory, CheckAbsolutePath);
    v.Double("save_period_s", o.state.save_period_s, 0.1, 3600.0);
    v.Int("writer_queue_capacity", o.state.writer_queue_capacity, 1, 1024);
  });
  v.Section("scheduling", [&] {
    SchedulingOptions& s = o.scheduling;
    v.Enum("policy", s.policy, kSchedPolicyNames);
    v.Int("priority", s.priority, 0, 99);
    v.IntList("cpu_affinity", s.cpu_affinity, 0, 1023, 1024);
    v.Bool("mlockall", s.mlockall);
  });
}

// Rules between keys. report(key, message) is called once per broken rule, naming the key
// whose value should change. A rule runs only when every key it reads is usable(key) (the
// loader passes the keys without an error of their own, so that a file with a value out of
// range still has its other rules checked in the same run; default: every key).
void CrossCheck(
    const DaemonOptions& o,
    const std::function<void(const std::string& key, const std::string& message)>& report,
    const std::function<bool(const std::string& key)>& usable = {});

}  // namespace atlas::config
