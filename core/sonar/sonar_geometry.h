#pragma once
// Wide-beam sonar interpretation for line features (paper, Section IV and Fig. 9; the
// "wide-beam" model after Leonard and Durrant-Whyte, and Leonard and Rikoski's delayed decision
// making for feature initialisation).
//
// A Polaroid-like transducer reports the range r of the first echo in its cone. A planar
// surface echoes only near normal incidence, so a return from a wall says: the wall's line is
// tangent to the arc of radius r around the transducer, at a point inside the cone. Its normal
// (pointing from the transducer to the line) makes an angle phi with the transducer's heading,
// |phi| <= beam_width / 2, and
//
//   rho_in_transducer_frame = r.                                         (measurement model)
//
// Lines are (rho, alpha) as in core/localmap/line_model.h. Jacobians are with respect to the
// robot pose (x, y, theta) and the map line (rho, alpha).

#include <Eigen/Core>

#include "core/common/sensor_types.h"
#include "core/geometry/se2.h"

namespace atlas {

// The predicted range of the transducer `mount` (on the robot at `robot`) to the map line
// (rho, alpha). `incidence` is the signed angle phi of the line's normal (from the transducer
// to the line) from the transducer's heading; h = beam_width / 2.
// - |phi| <= h (`in_cone`): the echo comes back along the normal, range = distance d from the
//   transducer to the line; `foot` is the tangent point.
// - h < |phi| <= h + edge_incidence (`edge_echo`): the ray at the cone's edge meets the wall at
//   incidence psi = |phi| - h, within the critical angle of a specular surface, and echoes back
//   along itself: range = d / cos(psi); `foot` is where the edge ray meets the line. With
//   edge_incidence = 0 there are no edge echoes (pure tangent model).
// Otherwise the line cannot echo (`echoes` false) and `range` is d. Jacobians are those of the
// predicted range.
struct SonarRangePrediction {
  double range = 0.0;
  bool in_cone = false;
  bool edge_echo = false;
  double incidence = 0.0;  // signed angle of the line normal from the transducer heading
  Vec2 foot = Vec2::Zero();
  Eigen::RowVector3d d_pose = Eigen::RowVector3d::Zero();
  Eigen::RowVector2d d_line = Eigen::RowVector2d::Zero();
  bool echoes() const { return in_cone || edge_echo; }
};
SonarRangePrediction PredictSonarRange(const Pose2& robot, const SonarTransducer& mount, double rho,
                                       double alpha, double edge_incidence = 0.0);

// The part of the line (rho, alpha) inside the cone (half angle `half`) of the transducer pose
// `sensor` (same frame), as positions along the line (PositionAlongLine, line_model.h): the
// interval between the edge rays' crossings, unbounded (+-infinity) on the side of an edge ray
// that does not cross the line in front of the transducer. A return paired with the line came
// from somewhere in there; false (lo, hi unchanged) when no ray of the cone meets the line
// (half < pi / 2).
bool ConeFootprint(const Pose2& sensor, double half, double rho, double alpha, double& lo,
                   double& hi);

// The line tangent to the arc of radius `range` around the transducer pose `sensor` (in any
// frame) at the normal angle sensor.theta + phi: canonical (rho, alpha) in that frame.
Vec2 TangentLine(const Pose2& sensor, double range, double phi);

// The lines tangent to two arcs (centres at the transducer poses s1 and s2, radii r1 and r2)
// with both transducers on the same side of the line, and with the normal inside both cones
// (half angles h1, h2). Writes up to two canonical lines to `out`; returns how many.
int CommonTangentLines(const Pose2& s1, double r1, double h1, const Pose2& s2, double r2, double h2,
                       Vec2 out[2]);

}  // namespace atlas
