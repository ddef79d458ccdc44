#pragma once
// TUM RGB-D benchmark trajectories (docs/formats.md, "TUM trajectory"), as evo, the TUM
// benchmark scripts and rpg_trajectory_evaluation read them: one pose per line,
//
//   timestamp tx ty tz qx qy qz qw
//
// seconds; metres; the orientation as a unit quaternion (Hamilton, scalar last). A planar pose
// (x, y, theta) is written with tz = 0 and the rotation about z, (0, 0, sin(theta/2),
// cos(theta/2)).

#include <span>
#include <string>
#include <string_view>
#include <vector>

#include "core/eval/timed_trajectory.h"

namespace atlas::formats {

// "# <comment>", then one row per pose, space-separated: the stamp with 6 decimals, positions
// with 6, the quaternion with 9.
std::string FormatTumTrajectory(std::span<const eval::TimedPose> poses, std::string_view comment);

// Appends the rows of `text` to `out`, each reduced to the plane: x, y and the heading of the
// quaternion's rotation about z. "" or "<source>:<line>: <what>". Refused: a bad number, a
// stamp, position or angle beyond text_rows.h's limits, a quaternion whose norm is not 1 (to
// 1e-6), and a pose not in the plane (tz beyond 1e-6 m or a rotation axis off z).
std::string ParseTumTrajectory(std::string_view text, const std::string& source,
                               std::vector<eval::TimedPose>* out);

}  // namespace atlas::formats
