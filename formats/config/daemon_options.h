#pragma once
// Every option of atlasd, as read from one TOML file (config/atlasd.toml documents each key).
//
// One plain struct per module, all gathered in DaemonOptions. Defaults here are the defaults of
// the daemon: a key absent from the file keeps its default. The keys that configure the mapper
// take their defaults from the core modules' options (MapperDefaults() below), converted to the
// file's units, so that each setting has one default. Units are in the field names
// (_m metres, _deg degrees, _s seconds, _ms milliseconds); angles without a unit suffix are
// radians. The modules that consume these (drivers, atlas, local maps, the loop) copy the fields
// they need into their own options structs.
//
// The key of every field in the file is "<section>.<field>", e.g. laser.baud, laser.mount.x_m,
// lcm.channels.pose; config_schema.h is the single list of keys, types and ranges.

#include <chrono>
#include <cmath>
#include <cstdint>
#include <string>
#include <vector>

#include "core/mapper/mapper_factory.h"
#include "core/mapper/step_loop.h"
#include "core/sonar/sonar_options.h"
#include "drivers/sick/lms_messages.h"

namespace atlas {

// The mapper's and the step loop's default options (core/mapper), which the mapper's keys
// default to.
inline const MapperSettings& MapperDefaults() {
  static const MapperSettings s;
  return s;
}
inline const StepLoopOptions& StepLoopDefaults() {
  static const StepLoopOptions l;
  return l;
}
// Radians of a default in the file's degrees (the config converts back with * M_PI / 180).
inline double DegreesOf(double radians) { return radians / (M_PI / 180.0); }

// A sensor's pose on the robot, in the robot (base) frame.
struct MountPose {
  double x_m = 0.0;
  double y_m = 0.0;
  double theta_deg = 0.0;
};

// SICK LMS-2xx on a serial line (docs/devices.md, section 1).
struct LaserOptions {
  bool enabled = true;
  std::string device = "/dev/ttyUSB0";
  int baud = 500000;                    // 9600, 19200, 38400 or 500000
  int angular_range_deg = 180;          // 180 or 100
  double angular_resolution_deg = 1.0;  // 1.0, 0.5 or 0.25 (0.25 only with 100 degrees)
  sick::Unit unit = sick::Unit::kMillimetre;
  double max_range_m = 8.0;  // the scanner's range setting (its reader applies it)
  MountPose mount{0.1, 0.0, 0.0};
  int queue_capacity = 8;  // scans between the reader thread and the loop
  // A scan was taken at its arrival stamp + time_offset_s (negative: before it), seconds: the
  // loop looks the odometry up there (core/mapper/step_loop.h says why). 0 on our robot
  // until calibrated (docs/config.md, "Laser time offset"); mit-csail needs about -0.1.
  double time_offset_s =
      std::chrono::duration<double>(StepLoopDefaults().laser_time_offset).count();
};

// AgileX base odometry on CAN (docs/devices.md, section 2).
struct OdometryOptions {
  // A SocketCAN interface name ("can0") or "unix:PATH" for the fake bus.
  std::string interface = "can0";
  double track_width_m = MapperDefaults().local_map.odometry.track_width;
  // A wheel-distance change faster than this is a counter discontinuity, not motion.
  double max_speed_mps = 3.0;
  // Allowance on top of max_speed_mps * dt, for stamp jitter and counter quantisation.
  double slack_m = 0.02;
  // After a longer gap between frames the counters are re-referenced (a discontinuity).
  double max_gap_s = 1.0;
  int queue_capacity = 64;  // odometry samples between the reader thread and the loop
};

enum class SonarRing { kP3dx16, kB21_24 };

// Pioneer P2OS sonar ring on a serial line (docs/devices.md, section 3).
struct SonarOptions {
  bool enabled = false;
  std::string device = "/dev/ttyS0";
  int baud = 9600;  // 9600, 19200, 38400, 57600 or 115200
  SonarRing ring = SonarRing::kP3dx16;
  double range_factor_mm = 1.0;  // millimetres per controller range unit
  int queue_capacity = 32;
};

// What a laser map-frame holds: ten lines in an EKF (core/localmap/line_ekf_map.h) or a
// probability grid of its scans (core/gridmap/grid_local_map.h; docs/design.md, "Dense frames").
enum class LocalMapKind { kLines, kGrid };

struct LocalMapConfig {
  // Which range sensors the local maps use: the laser alone (line EKF, core/localmap), the
  // sonar ring alone, or both in one EKF (core/sonar SonarLocalMap). "sonar" and "both" need
  // sonar.enabled, "both" also laser.enabled.
  RangeSensors sensors = MapperDefaults().sensors;
  // With the laser alone: "lines" or "grid".
  LocalMapKind kind = MapperDefaults().grid_frames ? LocalMapKind::kGrid : LocalMapKind::kLines;
  // With the sonar alone: the sonar w of eq. 12 (core/sonar/sonar_map_bootstrapper.h) solves
  // traversal juveniles' poses from their readings (the default); false: they keep their seeded
  // pose (docs/design.md, "Sonar local maps").
  bool sonar_bootstrap = MapperDefaults().sonar_bootstrap;
};

// Scan-to-scan matching of consecutive laser scans (core/scanmatch/scan_matcher.h): the wheel
// odometry's increment is the prior; the matched increment and its covariance replace it in
// the local maps' prediction. The remaining matcher options keep core/scanmatch's defaults.
struct ScanMatchConfig {
  bool enabled = MapperDefaults().scan_match.enabled;
  // returns beyond are not matched
  double max_range_m = MapperDefaults().scan_match.max_range;
  // point-to-line residual noise
  double point_sigma_m = MapperDefaults().scan_match.point_sigma;
  // the matcher's information is multiplied by this
  double information_scale = MapperDefaults().scan_match.information_scale;
  // search either side of the odometry's heading (0: none)
  double heading_search_deg = DegreesOf(MapperDefaults().scan_match.heading_search);
};

// Odometry error model of the local maps (core/localmap OdometryNoiseOptions): each sigma is
// the standard deviation after one unit of motion; variances grow linearly with the motion
// (sigma with its square root). The calibration errors grow with the motion itself. Defaults:
// core/localmap's (the B21 of the mit-csail log), the square roots of its variances.
struct OdometryErrorConfig {
  // metres per metre rolled, each wheel
  double wheel_sigma_per_m = std::sqrt(MapperDefaults().local_map.odometry.wheel_var_per_m);
  // metres per metre driven, each of x and y
  double translation_sigma_per_m = std::sqrt(MapperDefaults().local_map.odometry.xy_var_per_m);
  // metres per radian turned
  double translation_sigma_per_rad = std::sqrt(MapperDefaults().local_map.odometry.xy_var_per_rad);
  // radians of heading per metre driven
  double rotation_sigma_per_m = std::sqrt(MapperDefaults().local_map.odometry.theta_var_per_m);
  // radians of heading per radian turned
  double rotation_sigma_per_rad = std::sqrt(MapperDefaults().local_map.odometry.theta_var_per_rad);
  // relative wheel radius error
  double wheel_scale_sigma = MapperDefaults().local_map.odometry.wheel_scale_sigma;
  // relative track width error
  double track_width_sigma = MapperDefaults().local_map.odometry.track_width_sigma;
};

struct LaserNoiseOptions {
  double range_sigma_m = MapperDefaults().local_map.extraction.range_sigma;
  // Walls are not straight to the centimetre: extra noise normal to a line per point, and
  // floors on a fitted line's (rho, alpha) standard deviations.
  double wall_sigma_m = MapperDefaults().local_map.extraction.model_sigma;
  double line_rho_sigma_min_m = MapperDefaults().local_map.extraction.min_rho_sigma;
  double line_alpha_sigma_min_deg =
      DegreesOf(MapperDefaults().local_map.extraction.min_alpha_sigma);
};

struct NoiseOptions {
  OdometryErrorConfig odometry;
  LaserNoiseOptions laser;
};

// The Atlas framework's parameters (paper, Sections I-A and III): the fields of AtlasOptions
// (core/atlas/atlas.h) and LocalMapOptions::capacity that the file sets.
struct AtlasParameters {
  // features a local map may hold (map capacity, Section I-A)
  int map_capacity = MapperDefaults().local_map.capacity;
  // juvenile + mature hypotheses alive at once
  int max_hypotheses = MapperDefaults().atlas.max_hypotheses;
  // steps a juvenile hypothesis has to mature (Section III-E)
  int probation_steps = MapperDefaults().atlas.lifecycle.probation_scans;
  // hysteresis of the dominant hypothesis's q (Section III-B)
  double switch_margin = MapperDefaults().atlas.lifecycle.switch_margin;
  // alpha and the sigmas (metres, metres, radians) of the quality metric q, eq. 5
  double quality_alpha = MapperDefaults().atlas.quality.alpha;
  double max_sigma_x = MapperDefaults().atlas.quality.sigma_x;
  double max_sigma_y = MapperDefaults().atlas.quality.sigma_y;
  double max_sigma_theta = MapperDefaults().atlas.quality.sigma_theta;
  // Work budget: frames the bounded Dijkstra projection settles per step, nearest first; the
  // candidates for traversal and map-matching come from them (4 left loops of more than 3
  // frames unclosed).
  int frames_examined_per_step = MapperDefaults().atlas.projection_max_frames;
  // work budget: map-matching candidates per step
  int match_candidates_per_step = MapperDefaults().atlas.match_candidates_per_step;
};

// LCM channel names (at most 63 characters, no whitespace, all different).
struct LcmChannels {
  std::string pose = "ATLAS_POSE";
  std::string reference_pose = "ATLAS_REFERENCE_POSE";
  std::string local_map = "ATLAS_LOCAL_MAP";
  std::string graph = "ATLAS_GRAPH";
  std::string hypotheses = "ATLAS_HYPOTHESES";
  std::string health = "ATLAS_HEALTH";
  std::string raw_odometry = "ATLAS_RAW_ODOMETRY";
  std::string raw_laser = "ATLAS_RAW_LASER";
  std::string raw_sonar = "ATLAS_RAW_SONAR";
};

struct LcmOptions {
  // ttl=0 keeps the multicast on this host; set ttl=1 to reach the robot's LAN.
  std::string url = "udpm://239.255.76.67:7667?ttl=0";
  bool republish_raw = false;
  double health_period_s = 1.0;
  double graph_period_s = 1.0;
  double local_map_period_s = 0.2;
  // The frame ATLAS_REFERENCE_POSE places the pose in (frame 0 is the first frame).
  int reference_frame = 0;
  LcmChannels channels;
};

// Where atlasd's laser scans and odometry come from (docs/lcm.md, "LCM input"): the devices of
// [laser] and [odometry], or messages on LCM (lcm.url), stamped with their arrival time like a
// device's data. Message types: atlasd's own (atlasd.laser_scan_t, atlasd.odometry_t, what
// lcm.republish_raw publishes) or libbot's (bot_core.planar_lidar_t, bot_core.pose_t).
enum class InputSource { kDevices, kLcm };
enum class LaserMessageType { kLaserScan, kPlanarLidar };
enum class OdometryMessageType { kOdometry, kBotPose };

struct InputOptions {
  InputSource source = InputSource::kDevices;
  LaserMessageType laser_type = LaserMessageType::kLaserScan;
  OdometryMessageType odometry_type = OdometryMessageType::kOdometry;
  // Defaults: the raw channels atlasd republishes on (a recording of one atlasd feeds another).
  std::string laser_channel = LcmChannels{}.raw_laser;
  std::string odometry_channel = LcmChannels{}.raw_odometry;
};

struct LoopOptions {
  // fixed work budget of one atlas step
  double step_budget_ms =
      std::chrono::duration<double, std::milli>(StepLoopDefaults().step_budget).count();
  // older scans are dropped (and counted) beyond this
  int max_pending_scans = StepLoopDefaults().max_pending_scans;
};

struct StateOptions {
  std::string directory = "/var/lib/atlasd";  // must be absolute
  double save_period_s = 2.0;                 // snapshot batch period of the store writer
  int writer_queue_capacity = 4;              // snapshot batches waiting for the writer
};

enum class SchedPolicy { kOther, kFifo, kRoundRobin };

struct SchedulingOptions {
  // Real-time by default (config/atlasd.toml says why); unprivileged without RLIMIT_RTPRIO it
  // is reported and atlasd runs with "other".
  SchedPolicy policy = SchedPolicy::kFifo;
  int priority = 40;              // 0 for "other", 1..99 for "fifo" and "rr"
  std::vector<int> cpu_affinity;  // empty: any CPU
  bool mlockall = false;
};

struct DaemonOptions {
  InputOptions input;
  LaserOptions laser;
  OdometryOptions odometry;
  SonarOptions sonar;
  NoiseOptions noise;
  LocalMapConfig localmap;
  ScanMatchConfig scan_match;
  AtlasParameters atlas;
  LcmOptions lcm;
  LoopOptions loop;
  StateOptions state;
  SchedulingOptions scheduling;

  // Empty when every field is in range and the fields agree with each other; otherwise one
  // line per problem, each naming the key ("laser.baud: must be one of ...").
  std::string Validate() const;
};

}  // namespace atlas
