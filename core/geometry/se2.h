#pragma once
// Rigid transforms of the plane, SE(2), in the notation of Smith, Self and Cheeseman as the
// Atlas paper uses it (Bosse, Newman, Leonard, Teller):
//
//   a (+) b        Compose: b expressed in a's frame, then a applied.           eq. 2, 10
//   (-) a          Inverse.                                                      eq. 15
//   a (-) b        Between(a, b) = (-)a (+) b: the pose of b seen from a.       (relative pose)
//
// Every pose is (x, y, theta) with theta wrapped to (-pi, pi]. Jacobians are with respect to
// (x, y, theta) of each argument. Covariance propagation to first order:
//
//   Sigma_ac = J1 Sigma_ab J1^T + J2 Sigma_bc J2^T                               eq. 2, 11
//
// Operands are treated as independent; callers holding correlated poses must propagate the
// joint covariance themselves.

#include <Eigen/Core>
#include <cmath>
#include <numbers>

namespace atlas {

using Mat3 = Eigen::Matrix3d;
using Vec3 = Eigen::Vector3d;
using Vec2 = Eigen::Vector2d;

// Wraps an angle to (-pi, pi].
double WrapAngle(double a);

struct Pose2 {
  double x = 0.0;
  double y = 0.0;
  double theta = 0.0;

  Vec3 ToVector() const { return Vec3(x, y, theta); }
  bool IsFinite() const { return std::isfinite(x) && std::isfinite(y) && std::isfinite(theta); }
  static Pose2 FromVector(const Vec3& v) { return Pose2{v.x(), v.y(), WrapAngle(v.z())}; }
  // Maps a point given in this pose's frame into the parent frame.
  Vec2 TransformPoint(const Vec2& p) const;
};

// Pose2::TransformPoint for many points: the pose's cosine and sine evaluated once.
struct RigidTransform {
  explicit RigidTransform(const Pose2& p) : pose(p), c(std::cos(p.theta)), s(std::sin(p.theta)) {}
  Vec2 Apply(const Vec2& q) const {
    return Vec2(pose.x + c * q.x() - s * q.y(), pose.y + s * q.x() + c * q.y());
  }
  Pose2 pose;
  double c, s;
};

// a (+) b.
Pose2 Compose(const Pose2& a, const Pose2& b);
// (-) a.
Pose2 Inverse(const Pose2& a);
// a (-) b = (-)a (+) b: b expressed in the frame of a.
Pose2 Between(const Pose2& a, const Pose2& b);
// The pose a fraction f of the way from a to b: linear in x and y, the heading along the shorter
// arc (wrapped); f in [0, 1] interpolates, f > 1 extrapolates. For odometry and ground truth
// sampled densely enough that the motion between samples is nearly straight.
Pose2 InterpolatePose(const Pose2& a, const Pose2& b, double f);

// J1 = d(a (+) b)/da and J2 = d(a (+) b)/db.
Mat3 ComposeJacobianA(const Pose2& a, const Pose2& b);
Mat3 ComposeJacobianB(const Pose2& a);
// J(-) = d((-)a)/da.
Mat3 InverseJacobian(const Pose2& a);

// A Gaussian pose: mean and 3x3 covariance over (x, y, theta).
struct UncertainPose {
  Pose2 mean;
  Mat3 cov = Mat3::Zero();
};

// eq. 2: composition with covariance, operands independent.
UncertainPose Compose(const UncertainPose& a, const UncertainPose& b);
// Inverse with covariance J(-) Sigma J(-)^T.
UncertainPose Inverse(const UncertainPose& a);
// a (-) b with covariance, operands independent (eq. 15 with Sigma_a, Sigma_b).
UncertainPose Between(const UncertainPose& a, const UncertainPose& b);

}  // namespace atlas
