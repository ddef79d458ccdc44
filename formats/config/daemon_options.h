#pragma once
// Every option of atlasd, as read from one TOML file (config/atlasd.toml documents each key).
//
// One plain struct per module, all gathered in DaemonOptions. Defaults here are the defaults of
// the daemon: a key absent from the file keeps its default. Units are in the field names
// (_m metres, _deg degrees, _s seconds, _ms milliseconds); angles without a unit suffix are
// radians. The modules that consume these (drivers, atlas, local maps, the loop) copy the fields
// they need into their own options structs.
//
// The key of every field in the file is "<section>.<field>", e.g. laser.baud, laser.mount.x_m,
// lcm.channels.pose; config_schema.h is the single list of keys, types and ranges.

#include <cstdint>
#include <string>
#include <vector>

#include "core/sonar/sonar_options.h"
#include "drivers/sick/lms_messages.h"

namespace atlas {

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
  double max_range_m = 8.0;
  MountPose mount{0.1, 0.0, 0.0};
  int queue_capacity = 8;  // scans between the reader thread and the loop
  // A scan was taken at its arrival stamp + time_offset_s (negative: before it), seconds: the
  // loop looks the odometry up there (core/mapper/step_loop.h says why). 0 on our robot
  // until calibrated (docs/config.md, "Laser time offset"); mit-csail needs about -0.1.
  double time_offset_s = 0.0;
};

// AgileX base odometry on CAN (docs/devices.md, section 2).
struct OdometryOptions {
  // A SocketCAN interface name ("can0") or "unix:PATH" for the fake bus.
  std::string interface = "can0";
  double track_width_m = 0.58;
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
  RangeSensors sensors = RangeSensors::kLaser;
  // With the laser alone: "lines" or "grid".
  LocalMapKind kind = LocalMapKind::kLines;
  // With the sonar alone: the sonar w of eq. 12 (core/sonar/sonar_map_bootstrapper.h) solves
  // traversal juveniles' poses from their readings (the default); false: they keep their seeded
  // pose (docs/design.md, "Sonar local maps").
  bool sonar_bootstrap = true;
};

// Scan-to-scan matching of consecutive laser scans (core/scanmatch/scan_matcher.h): the wheel
// odometry's increment is the prior; the matched increment and its covariance replace it in
// the local maps' prediction. The remaining matcher options keep core/scanmatch's defaults.
struct ScanMatchConfig {
  bool enabled = true;
  double max_range_m = 20.0;        // returns beyond are not matched
  double point_sigma_m = 0.03;      // point-to-line residual noise
  double information_scale = 0.3;   // the matcher's information is multiplied by this
  double heading_search_deg = 0.0;  // search either side of the odometry's heading (0: none)
};

// Odometry error model of the local maps (core/localmap OdometryNoiseOptions): each sigma is
// the standard deviation after one unit of motion; variances grow linearly with the motion
// (sigma with its square root). The calibration errors grow with the motion itself. Defaults:
// the B21 of the mit-csail log (measured with atlas-replay; docs/design.md, "Laser line local
// map"), a base whose odometry turns a few degrees wrong in a second: generous for a well
// calibrated base.
struct OdometryErrorConfig {
  double wheel_sigma_per_m = 0.01;          // metres per metre rolled, each wheel
  double translation_sigma_per_m = 0.0316;  // metres per metre driven, each of x and y
  double translation_sigma_per_rad = 0.01;  // metres per radian turned
  double rotation_sigma_per_m = 0.0707;     // radians of heading per metre driven
  double rotation_sigma_per_rad = 0.173;    // radians of heading per radian turned
  double wheel_scale_sigma = 0.0;           // relative wheel radius error
  double track_width_sigma = 0.0;           // relative track width error
};

struct LaserNoiseOptions {
  double range_sigma_m = 0.01;
  // Walls are not straight to the centimetre: extra noise normal to a line per point, and
  // floors on a fitted line's (rho, alpha) standard deviations.
  double wall_sigma_m = 0.03;
  double line_rho_sigma_min_m = 0.03;
  double line_alpha_sigma_min_deg = 1.15;
};

struct NoiseOptions {
  OdometryErrorConfig odometry;
  LaserNoiseOptions laser;
};

// The Atlas framework's parameters (paper, Sections I-A and III). Generic on purpose: the atlas
// and local-map modules fill their own options structs from these fields.
struct AtlasParameters {
  int map_capacity = 10;          // features a local map may hold (map capacity, Section I-A)
  int max_hypotheses = 8;         // juvenile + mature hypotheses alive at once
  int probation_steps = 20;       // steps a juvenile hypothesis has to mature (Section III-E)
  double switch_margin = 0.0;     // hysteresis of the dominant hypothesis's q (Section III-B)
  double quality_alpha = 0.5;     // alpha of the quality metric q, eq. 5
  double max_sigma_x = 1.0;       // sigma_x of eq. 5, metres
  double max_sigma_y = 1.0;       // sigma_y of eq. 5, metres
  double max_sigma_theta = 0.35;  // sigma_theta of eq. 5, radians
  // Work budget: frames the bounded Dijkstra projection settles per step, nearest first; the
  // candidates for traversal and map-matching come from them (4 left loops of more than 3
  // frames unclosed).
  int frames_examined_per_step = 24;
  int match_candidates_per_step = 2;  // work budget: map-matching candidates per step
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

struct LoopOptions {
  double step_budget_ms = 10.0;  // fixed work budget of one atlas step
  int max_pending_scans = 2;     // older scans are dropped (and counted) beyond this
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
