#pragma once
// Formats a simulated run as CARMEN log lines (docs/formats.md, "Simulated run"), so that every
// CARMEN-reading tool reads a simulated run. Pure string formatting; the caller owns the file.
//
//   ODOM x y theta tv rv accel ipc_timestamp hostname logger_timestamp
//   FLASER n r1..rn x y theta odom_x odom_y odom_theta ipc_timestamp hostname logger_timestamp
//       x y theta = the laser's pose from odometry; no return written as kCarmenNoReturn
//   SONAR n t1 r1 .. tn rn odom_x odom_y odom_theta ipc_timestamp hostname logger_timestamp
//       project-specific (not CARMEN): n (transducer index, range m) pairs, -1 = no echo;
//       CARMEN readers ignore it as an unknown message.
// Ranges are printed in millimetres precision, poses to 0.1 mm / 1e-5 rad, stamps to 1 us.

#include <string>

#include "core/common/sensor_types.h"

namespace atlas::sim {

// The SICK LMS no-return code as it appears in CARMEN logs (8191 cm).
inline constexpr double kCarmenNoReturn = 81.91;
inline constexpr const char* kSimHostname = "atlas-sim";

// `hostname`: the lines' hostname field (a word without spaces).
void AppendOdomLine(std::string* out, const OdometrySample& odometry, double tv, double rv,
                    const char* hostname = kSimHostname);
void AppendFlaserLine(std::string* out, const LaserScan& scan, const Pose2& odometry,
                      const char* hostname = kSimHostname);
void AppendSonarLine(std::string* out, const SonarReading& reading, const Pose2& odometry);
// "timestamp x y theta" (tab separated), the ground-truth TSV row.
void AppendTruthRow(std::string* out, const TruthSample& truth);

}  // namespace atlas::sim
