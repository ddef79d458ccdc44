#include "drivers/agilex/wheel_odometry.h"

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

namespace atlas::agilex {
namespace {

Time Ms(int64_t ms) { return Time(std::chrono::milliseconds(ms)); }

WheelOdometryOptions Options() {
  WheelOdometryOptions o;
  o.track_width_m = 0.5;
  o.max_speed_mps = 3.0;
  o.slack_m = 0.02;
  return o;
}

TEST(WheelOdometryOptions, Validate) {
  EXPECT_EQ(WheelOdometryOptions{}.Validate(), "");
  WheelOdometryOptions o;
  o.track_width_m = -0.1;
  EXPECT_NE(o.Validate(), "");
  o = {};
  o.max_speed_mps = 0.0;
  EXPECT_NE(o.Validate(), "");
  o = {};
  o.slack_m = std::nan("");
  EXPECT_NE(o.Validate(), "");
  o = {};
  o.max_gap_s = 0.0;
  EXPECT_NE(o.Validate().find("max_gap_s"), std::string::npos);
  o.max_gap_s = INFINITY;
  EXPECT_NE(o.Validate(), "");
}

TEST(WheelOdometry, FirstSampleIsTheReference) {
  WheelOdometryIntegrator odo(Options());
  EXPECT_EQ(odo.Update(Ms(0), {123456, -98765}), OdometryStep::kFirst);
  EXPECT_EQ(odo.sample().pose.x, 0.0);
  EXPECT_EQ(odo.sample().stamp, Ms(0));
}

TEST(WheelOdometry, StraightLine) {
  WheelOdometryIntegrator odo(Options());
  odo.Update(Ms(0), {5000, 5000});
  for (int i = 1; i <= 50; ++i) {
    ASSERT_EQ(odo.Update(Ms(20 * i), {5000 + 20 * i, 5000 + 20 * i}), OdometryStep::kIntegrated);
  }
  EXPECT_NEAR(odo.sample().pose.x, 1.0, 1e-12);
  EXPECT_NEAR(odo.sample().pose.y, 0.0, 1e-12);
  EXPECT_NEAR(odo.sample().pose.theta, 0.0, 1e-12);
  EXPECT_EQ(odo.sample().stamp, Ms(1000));
}

TEST(WheelOdometry, TurnOnTheSpot) {
  WheelOdometryIntegrator odo(Options());
  odo.Update(Ms(0), {0, 0});
  for (int i = 1; i <= 25; ++i) odo.Update(Ms(20 * i), {-10 * i, 10 * i});
  // dtheta = (0.01 + 0.01) / 0.5 = 0.04 rad per step.
  EXPECT_NEAR(odo.sample().pose.theta, 1.0, 1e-12);
  EXPECT_NEAR(odo.sample().pose.x, 0.0, 1e-12);
  EXPECT_NEAR(odo.sample().pose.y, 0.0, 1e-12);
}

TEST(WheelOdometry, ConstantCurvatureFollowsTheCircle) {
  WheelOdometryIntegrator odo(Options());
  odo.Update(Ms(0), {0, 0});
  // dl = 9 mm, dr = 11 mm: ds = 0.01 m, dtheta = 0.004 rad, radius 2.5 m.
  const int steps = 300;
  for (int i = 1; i <= steps; ++i) odo.Update(Ms(20 * i), {9 * i, 11 * i});
  const double theta = steps * 0.004;
  EXPECT_NEAR(odo.sample().pose.x, 2.5 * std::sin(theta), 1e-9);
  EXPECT_NEAR(odo.sample().pose.y, 2.5 * (1 - std::cos(theta)), 1e-9);
  EXPECT_NEAR(odo.sample().pose.theta, theta, 1e-9);
}

TEST(WheelOdometry, BaseRebootIsADiscontinuityAndIntegrationResumes) {
  WheelOdometryIntegrator odo(Options());
  odo.Update(Ms(0), {5000, 5000});
  odo.Update(Ms(20), {5040, 5040});
  const Pose2 before = odo.sample().pose;
  EXPECT_EQ(odo.Update(Ms(40), {0, 0}), OdometryStep::kDiscontinuity);
  EXPECT_EQ(odo.sample().pose.x, before.x);
  EXPECT_EQ(odo.discontinuities(), 1u);
  EXPECT_EQ(odo.Update(Ms(60), {30, 30}), OdometryStep::kIntegrated);
  EXPECT_NEAR(odo.sample().pose.x, 0.04 + 0.03, 1e-12);
}

TEST(WheelOdometry, Int32WrapIsADiscontinuity) {
  WheelOdometryIntegrator odo(Options());
  odo.Update(Ms(0), {2147483000, 0});
  EXPECT_EQ(odo.Update(Ms(20), {-2147483000, 10}), OdometryStep::kDiscontinuity);
  EXPECT_EQ(odo.sample().pose.x, 0.0);
  EXPECT_EQ(odo.Update(Ms(40), {-2147482990, 20}), OdometryStep::kIntegrated);
  EXPECT_NEAR(odo.sample().pose.x, 0.01, 1e-12);
}

TEST(WheelOdometry, PlausibilityScalesWithElapsedTime) {
  WheelOdometryIntegrator odo(Options());
  odo.Update(Ms(0), {0, 0});
  // 20 ms allow 3 m/s * 0.02 s + 0.02 m = 0.08 m.
  EXPECT_EQ(odo.Update(Ms(20), {79, 79}), OdometryStep::kIntegrated);
  EXPECT_EQ(odo.Update(Ms(40), {79 + 81, 79}), OdometryStep::kDiscontinuity);
  // Within max_gap_s (1 s), 0.15 s allow 0.47 m.
  EXPECT_EQ(odo.Update(Ms(190), {79 + 81 + 460, 79}), OdometryStep::kIntegrated);
  // A stamp that does not advance allows one frame period of the base: 0.08 m.
  EXPECT_EQ(odo.Update(Ms(190), {630, 89}), OdometryStep::kIntegrated);
  EXPECT_EQ(odo.Update(Ms(150), {630 + 81, 89}), OdometryStep::kDiscontinuity);
  EXPECT_EQ(odo.last_cause(), DiscontinuityCause::kImplausibleChange);
  EXPECT_EQ(odo.discontinuities(), 2u);
  EXPECT_EQ(odo.updates(), 6u);
}

// Two frames delayed on the bus arrive together: each covers one 20 ms period of motion at
// 2.5 m/s (0.05 m), which is plausible, and none of the motion is lost.
TEST(WheelOdometry, FramesArrivingTogetherAreIntegrated) {
  WheelOdometryIntegrator odo(Options());
  odo.Update(Ms(0), {0, 0});
  EXPECT_EQ(odo.Update(Ms(40), {50, 50}), OdometryStep::kIntegrated);
  EXPECT_EQ(odo.Update(Ms(40), {100, 100}), OdometryStep::kIntegrated);
  EXPECT_EQ(odo.Update(FromSeconds(0.0401), {150, 150}), OdometryStep::kIntegrated);
  EXPECT_EQ(odo.discontinuities(), 0u);
  EXPECT_NEAR(odo.sample().pose.x, 0.15, 1e-12);
  EXPECT_EQ(odo.sample().left_m, 0.15);
  EXPECT_EQ(odo.sample().right_m, 0.15);
}

TEST(WheelOdometry, RereferenceKeepsThePose) {
  WheelOdometryIntegrator odo(Options());
  odo.Update(Ms(0), {0, 0});
  odo.Update(Ms(20), {50, 50});
  odo.Rereference();
  // Even a change small enough to be motion is only the new reference.
  EXPECT_EQ(odo.Update(Ms(40), {60, 60}), OdometryStep::kRereferenced);
  EXPECT_EQ(odo.last_cause(), DiscontinuityCause::kRereferenced);
  EXPECT_NEAR(odo.sample().pose.x, 0.05, 1e-12);
  EXPECT_EQ(odo.Update(Ms(60), {70, 70}), OdometryStep::kIntegrated);
  EXPECT_NEAR(odo.sample().pose.x, 0.06, 1e-12);
  EXPECT_EQ(odo.discontinuities(), 1u);
}

TEST(WheelOdometry, RereferenceBeforeAnyCountersIsNotADiscontinuity) {
  WheelOdometryIntegrator odo(Options());
  odo.Rereference();
  EXPECT_EQ(odo.Update(Ms(0), {500, 500}), OdometryStep::kFirst);
  EXPECT_EQ(odo.discontinuities(), 0u);
}

// A base reboot: 3 s without frames, then counters reset to near zero. The reset (2 m back) is
// well within max_speed * 3 s, so only the gap gives it away: no pose jump, one discontinuity.
TEST(WheelOdometry, RebootAfterAGapIsOneDiscontinuityNotAJump) {
  WheelOdometryIntegrator odo(Options());
  odo.Update(Ms(0), {2000, 2000});
  ASSERT_EQ(odo.Update(Ms(20), {2040, 2040}), OdometryStep::kIntegrated);
  const Pose2 before = odo.sample().pose;
  EXPECT_EQ(odo.Update(Ms(3020), {3, 2}), OdometryStep::kRereferenced);
  EXPECT_EQ(odo.last_cause(), DiscontinuityCause::kGap);
  EXPECT_EQ(odo.sample().pose.x, before.x);
  EXPECT_EQ(odo.sample().pose.y, before.y);
  EXPECT_EQ(odo.sample().pose.theta, before.theta);
  EXPECT_EQ(odo.Update(Ms(3040), {23, 22}), OdometryStep::kIntegrated);
  EXPECT_NEAR(odo.sample().pose.x, 0.04 + 0.02, 1e-12);
  EXPECT_EQ(odo.discontinuities(), 1u);
  // The reader also re-references on the reconnect that the 3 s silence causes: still one.
  WheelOdometryIntegrator reopened(Options());
  reopened.Update(Ms(0), {2000, 2000});
  reopened.Update(Ms(20), {2040, 2040});
  reopened.Rereference();
  EXPECT_EQ(reopened.Update(Ms(3020), {3, 2}), OdometryStep::kRereferenced);
  EXPECT_NEAR(reopened.sample().pose.x, 0.04, 1e-12);
  EXPECT_EQ(reopened.discontinuities(), 1u);
}

}  // namespace
}  // namespace atlas::agilex
