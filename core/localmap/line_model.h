#pragma once
// Geometry of infinite lines (rho, alpha) under SE(2) — the measurement model of the
// line-feature EKF (Smith, Self and Cheeseman stochastic map; lines as in Arras & Siegwart,
// "Feature extraction and scene interpretation for map-based navigation", 1997).
//
// A line is the set { p : p . (cos alpha, sin alpha) = rho }. The canonical form has rho >= 0 and
// alpha in (-pi, pi]; (rho, alpha) and (-rho, alpha + pi) are the same line. Jacobians are with
// respect to (x, y, theta) of the pose and (rho, alpha) of the line.

#include <Eigen/Core>

#include "core/geometry/se2.h"

namespace atlas {

using Mat2 = Eigen::Matrix2d;
using Mat23 = Eigen::Matrix<double, 2, 3>;

// A line measured in the robot frame (features extracted from one scan).
struct ObservedLine {
  double rho = 0.0;  // canonical
  double alpha = 0.0;
  Mat2 cov = Mat2::Zero();
  Vec2 endpoint_a = Vec2::Zero();  // extent, on the line, in the same frame
  Vec2 endpoint_b = Vec2::Zero();
  int num_points = 0;
  int first_beam = -1;  // beam index range of the supporting points
  int last_beam = -1;

  double Length() const { return (endpoint_b - endpoint_a).norm(); }
};

// The canonical (rho, alpha) of the infinite line through the distinct points a and b.
Vec2 LineThroughPoints(const Vec2& a, const Vec2& b);

// Puts (rho, alpha) in canonical form; returns true if it flipped the sign (the covariance of
// a flipped line is D cov D with D = diag(-1, 1)).
bool CanonicalizeLine(double& rho, double& alpha);

// The line given in the frame of `pose` (child), expressed in the parent frame:
//   alpha_p = alpha_c + theta,  rho_p = rho_c + x cos(alpha_p) + y sin(alpha_p).
// Not canonicalised. Jacobians: d/dpose (2x3) and d/d(rho_c, alpha_c) (2x2).
struct LineTransform {
  Vec2 line;  // (rho, alpha)
  Mat23 d_pose;
  Mat2 d_line;
};
LineTransform LineToParent(const Pose2& pose, double rho_c, double alpha_c);

// An ObservedLine of one frame expressed in a parent frame, exactly (pose known), canonical.
ObservedLine ObservedLineToParent(const Pose2& pose, const ObservedLine& line);

// The predicted observation of the map line (rho, alpha) from the robot pose:
//   z = (rho - x cos(alpha) - y sin(alpha), alpha - theta),
// with Jacobians d_pose = dz/d(x, y, theta) and d_line = dz/d(rho, alpha).
struct LinePrediction {
  Vec2 z;
  Mat23 d_pose;
  Mat2 d_line;
};
LinePrediction PredictLine(const Pose2& robot, double rho, double alpha);

// Brings a prediction to the representation (rho, alpha) or (-rho, alpha + pi) whose angle is
// within pi/2 of `observed_alpha` (flipping its Jacobians with it) and returns the innovation
// observed - predicted with the angle wrapped. `flipped` (optional) tells whether it flipped.
Vec2 LineInnovation(const Vec2& observed, LinePrediction& prediction, bool* flipped = nullptr);

// Signed position of point p along the line (rho, alpha): p . (-sin alpha, cos alpha).
double PositionAlongLine(double alpha, const Vec2& p);
// The point of the line (rho, alpha) at position t along it.
Vec2 PointOnLine(double rho, double alpha, double t);

}  // namespace atlas
