#pragma once
// One line of a CARMEN log, parsed without any I/O: text in, record or typed error out.
//
// Formats (CARMEN readlog.c; all angles radians, distances metres, timestamps seconds):
//   ODOM x y theta tv rv accel ipc_timestamp hostname logger_timestamp
//   FLASER n r1..rn x y theta odom_x odom_y odom_theta ipc_timestamp hostname logger_timestamp
//   RAWLASER<k> type start_angle fov resolution max_range accuracy remission_mode
//       n r1..rn m e1..em ipc_timestamp hostname logger_timestamp                 (k = 1..4)
//   ROBOTLASER1 type start_angle fov resolution max_range accuracy remission_mode
//       n r1..rn m e1..em laser_x laser_y laser_theta x y theta tv rv
//       forward_safety_dist side_safety_dist turn_axis ipc_timestamp hostname logger_timestamp
//
// FLASER carries no beam geometry; as CARMEN does, it is guessed from the beam count: 180/181
// beams -> 1 deg apart, 360/361 -> 0.5 deg, 400/401 -> 0.25 deg, otherwise 180 deg spread
// evenly; the first beam is at -90 deg. For FLASER "x y theta" is the pose of the laser and
// "odom_x odom_y odom_theta" the robot's odometry pose, both in the odometry frame.
//
// Other message types (PARAM, NEFF, TRUTH, SYNC, RLASER, ...), '#' comments and blank lines
// are kIgnored. A first word that is not a message name (upper-case letters, digits, '_') is an
// error, so that a damaged keyword is not silently skipped.

#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "core/geometry/se2.h"

namespace atlas::carmen {

enum class LineKind { kIgnored, kOdometry, kLaser };

struct OdometryRecord {
  Pose2 pose;  // theta as written (not wrapped)
  double tv = 0.0, rv = 0.0, accel = 0.0;
  double ipc_timestamp = 0.0;
  std::string hostname;
  double logger_timestamp = 0.0;
};

struct LaserRecord {
  std::string message;  // "FLASER", "RAWLASER1".."RAWLASER4", "ROBOTLASER1"
  int laser_id = 1;     // 1 = front
  double start_angle = 0.0;
  double fov = 0.0;
  double angular_resolution = 0.0;
  double max_range = 0.0;              // 0 when the line does not state it (FLASER)
  std::vector<float> ranges;           // as written; no-return codes not yet mapped
  std::optional<Pose2> laser_pose;     // FLASER, ROBOTLASER1
  std::optional<Pose2> odometry_pose;  // FLASER, ROBOTLASER1
  double ipc_timestamp = 0.0;
  std::string hostname;
  double logger_timestamp = 0.0;
};

enum class LineError {
  kNone,
  kBadMessageName,  // first word is not a message name
  kMissingFields,   // line ends early
  kExtraFields,     // more fields than the format has
  kBadNumber,       // a field that must be a number is not one (or is not finite)
  kBadCount,        // a beam / remission count that is negative or absurd
  kBadRange,        // a negative range
};
const char* ToString(LineError e);

struct ParsedLine {
  LineKind kind = LineKind::kIgnored;
  std::string message;      // first word ("" for blank and comment lines)
  OdometryRecord odometry;  // kind == kOdometry
  LaserRecord laser;        // kind == kLaser
  LineError error = LineError::kNone;
  std::string reason;  // human-readable: which field, what was found
  bool ok() const { return error == LineError::kNone; }
};

// Beam counts above this are rejected as kBadCount (no planar laser has more).
inline constexpr int kMaxBeams = 100000;

// Parses one line (without its newline; a trailing '\r' is tolerated).
ParsedLine ParseLine(std::string_view line);

// The FLASER beam geometry CARMEN assumes for `num_beams` (see above).
double GuessFlaserFov(int num_beams);
double GuessFlaserAngleIncrement(int num_beams);

}  // namespace atlas::carmen
