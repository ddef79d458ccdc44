#include "sim/reference_odometry.h"

#include <gtest/gtest.h>

#include <cmath>
#include <string>

namespace atlas::carmen {
namespace {

// A corrected-style log: ODOM lines along a quarter circle of radius 2 m, a scan every 5th line.
CarmenLog QuarterCircleLog() {
  CarmenLogBuilder b(CarmenLogOptions::ForCorrectedLog(), "mem");
  for (int i = 0; i <= 100; ++i) {
    const double a = i * (M_PI / 2) / 100;
    const std::string pose = std::to_string(2 * std::sin(a)) + " " +
                             std::to_string(2 - 2 * std::cos(a)) + " " + std::to_string(a);
    if (i % 5 == 0) {
      EXPECT_TRUE(b.AddLine(i + 1, "FLASER 1 3.0 " + pose + " " + pose + " 0 h 0"));
    } else {
      EXPECT_TRUE(b.AddLine(i + 1, "ODOM " + pose + " 0 0 0 0 h 0"));
    }
  }
  return b.Finish();
}

WheelOdometryNoiseOptions NoErrors() {
  WheelOdometryNoiseOptions o;
  o.wheel_noise_per_m = 0.0;
  o.left_scale_error = o.right_scale_error = o.track_width_error = 0.0;
  return o;
}

TEST(ReferenceOdometryTest, NoiselessOdometryReproducesTheReference) {
  const CarmenLog log = QuarterCircleLog();
  ASSERT_EQ(log.reference.size(), 101u);
  ASSERT_EQ(log.events.size(), 21u);
  const auto events = EventsWithSynthesizedOdometry(log, NoErrors(), 1);
  ASSERT_EQ(events.size(), 122u);
  size_t k = 0;
  for (size_t i = 0; i < events.size(); ++i) {
    if (i > 0) {
      EXPECT_LE(StampOf(events[i - 1].event), StampOf(events[i].event));
    }
    if (const auto* o = std::get_if<OdometrySample>(&events[i].event)) {
      const Pose2& truth = log.reference[k++].truth.pose;
      EXPECT_NEAR(o->pose.x, truth.x, 1e-5);
      EXPECT_NEAR(o->pose.y, truth.y, 1e-5);
      EXPECT_NEAR(o->pose.theta, truth.theta, 1e-5);
    } else {
      // A scan directly follows the odometry sample of its own line.
      ASSERT_GT(i, 0u);
      EXPECT_TRUE(std::holds_alternative<OdometrySample>(events[i - 1].event));
      EXPECT_EQ(events[i - 1].line, events[i].line);
    }
  }
  EXPECT_EQ(k, 101u);
}

Pose2 LastOdometry(const std::vector<CarmenEvent>& events) {
  Pose2 last;
  for (const CarmenEvent& e : events) {
    if (const auto* o = std::get_if<OdometrySample>(&e.event)) last = o->pose;
  }
  return last;
}

TEST(ReferenceOdometryTest, NoiseIsSeededAndVisible) {
  const CarmenLog log = QuarterCircleLog();
  WheelOdometryNoiseOptions noisy;
  noisy.wheel_noise_per_m = 1e-3;
  const Pose2 a = LastOdometry(EventsWithSynthesizedOdometry(log, noisy, 7));
  const Pose2 b = LastOdometry(EventsWithSynthesizedOdometry(log, noisy, 7));
  const Pose2 c = LastOdometry(EventsWithSynthesizedOdometry(log, noisy, 8));
  const Pose2 truth = log.reference.back().truth.pose;
  EXPECT_EQ(a.x, b.x);
  EXPECT_EQ(a.theta, b.theta);
  EXPECT_NE(a.x, c.x);
  EXPECT_GT(std::hypot(a.x - truth.x, a.y - truth.y) + std::abs(a.theta - truth.theta), 1e-4);
}

}  // namespace
}  // namespace atlas::carmen
