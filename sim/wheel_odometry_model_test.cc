#include "sim/wheel_odometry_model.h"

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <vector>

namespace atlas {
namespace {

constexpr double kPi = std::numbers::pi;

WheelOdometryNoiseOptions NoErrors() {
  WheelOdometryNoiseOptions o;
  o.wheel_noise_per_m = 0.0;
  o.left_scale_error = 0.0;
  o.right_scale_error = 0.0;
  o.track_width_error = 0.0;
  return o;
}

// A wiggly path with turns, reversing and a bit of sideways slip, sampled at 50 Hz.
std::vector<TruthSample> WigglyPath() {
  std::vector<TruthSample> out;
  Pose2 p{3.0, -2.0, 0.7};
  for (int i = 0; i < 2000; ++i) {
    const double t = i * 0.02;
    const double v = 0.8 * std::sin(0.3 * t) + 0.2;
    const double w = 0.6 * std::sin(0.11 * t + 1.0);
    out.push_back(TruthSample{FromSeconds(t), p});
    p = Compose(p, Pose2{v * 0.02, 0.001 * std::sin(t), w * 0.02});
  }
  return out;
}

// Straight line of `length` metres along +x in 1 cm steps.
std::vector<TruthSample> StraightLine(double length) {
  std::vector<TruthSample> out;
  const int n = static_cast<int>(length / 0.01);
  for (int i = 0; i <= n; ++i) out.push_back({FromSeconds(i * 0.02), Pose2{i * 0.01, 0.0, 0.0}});
  return out;
}

TEST(WheelOdometryNoiseOptions, DefaultsValidAndBadRejected) {
  EXPECT_EQ(WheelOdometryNoiseOptions{}.Validate(), "");
  WheelOdometryNoiseOptions o;
  o.track_width_m = 0.0;
  EXPECT_NE(o.Validate(), "");
  o = {};
  o.wheel_noise_per_m = -1.0;
  EXPECT_NE(o.Validate(), "");
  o = {};
  o.track_width_error = std::nan("");
  EXPECT_NE(o.Validate(), "");
}

TEST(WheelOdometryModel, ZeroNoiseReproducesTruth) {
  WheelOdometryModel model(NoErrors(), 1);
  for (const TruthSample& t : WigglyPath()) {
    const OdometrySample o = model.Step(t);
    EXPECT_EQ(o.stamp, t.stamp);
    ASSERT_NEAR(o.pose.x, t.pose.x, 1e-9);
    ASSERT_NEAR(o.pose.y, t.pose.y, 1e-9);
    ASSERT_NEAR(WrapAngle(o.pose.theta - t.pose.theta), 0.0, 1e-9);
  }
}

TEST(WheelOdometryModel, FirstCallReturnsStartPose) {
  WheelOdometryModel model(WheelOdometryNoiseOptions{}, 7);
  const OdometrySample o = model.Step({FromSeconds(5.0), Pose2{1.0, 2.0, 0.3}});
  EXPECT_EQ(o.pose.x, 1.0);
  EXPECT_EQ(o.pose.y, 2.0);
  EXPECT_EQ(o.pose.theta, 0.3);
}

TEST(WheelOdometryModel, UnequalWheelRadiiDriftHeadingOnStraightLine) {
  WheelOdometryNoiseOptions opt = NoErrors();
  opt.left_scale_error = 0.002;
  opt.right_scale_error = -0.003;
  WheelOdometryModel model(opt, 1);
  OdometrySample last;
  for (const TruthSample& t : StraightLine(10.0)) last = model.Step(t);
  // dtheta = (d_r' - d_l') / b = 10 m * (-0.003 - 0.002) / 0.4 = -0.125 rad.
  EXPECT_NEAR(last.pose.theta, -0.125, 1e-6);
  // Mean scale (1 - 0.0005) shortens the path: arc length 9.995 m.
  const double chord = 9.995 * std::sin(0.0625) / 0.0625;
  EXPECT_NEAR(std::hypot(last.pose.x, last.pose.y), chord, 1e-6);
}

TEST(WheelOdometryModel, TrackWidthErrorScalesTurnsOnCircle) {
  WheelOdometryNoiseOptions opt = NoErrors();
  opt.track_width_error = 0.02;
  WheelOdometryModel model(opt, 1);
  // A circle of radius 2 m, driven once, in 1000 steps.
  const int n = 1000;
  double reported = 0.0;
  Pose2 prev_odom;
  for (int i = 0; i <= n; ++i) {
    const double a = 2.0 * kPi * i / n;
    const OdometrySample o =
        model.Step({FromSeconds(i * 0.02), Pose2{2.0 * std::sin(a), 2.0 - 2.0 * std::cos(a), a}});
    if (i > 0) reported += WrapAngle(o.pose.theta - prev_odom.theta);
    prev_odom = o.pose;
  }
  // Each turn is reported (1 + error) times as large: 2 pi * 1.02.
  EXPECT_NEAR(reported, 2.0 * kPi * 1.02, 1e-6);
}

TEST(WheelOdometryModel, SameSeedSameOutputDifferentSeedDifferent) {
  const auto path = WigglyPath();
  WheelOdometryModel a(WheelOdometryNoiseOptions{}, 42), b(WheelOdometryNoiseOptions{}, 42),
      c(WheelOdometryNoiseOptions{}, 43);
  Pose2 pa, pb, pc;
  for (const auto& t : path) {
    pa = a.Step(t).pose;
    pb = b.Step(t).pose;
    pc = c.Step(t).pose;
    ASSERT_EQ(pa.x, pb.x);
    ASSERT_EQ(pa.y, pb.y);
    ASSERT_EQ(pa.theta, pb.theta);
  }
  EXPECT_NE(pa.x, pc.x);
}

TEST(WheelOdometryModel, RandomNoiseVarianceGrowsWithDistance) {
  // Heading error of pure random noise on a straight line: var = 2 k L / b^2.
  WheelOdometryNoiseOptions opt = NoErrors();
  opt.wheel_noise_per_m = 1e-4;
  for (double length : {1.0, 4.0}) {
    const auto line = StraightLine(length);
    const int runs = 400;
    double sum = 0.0, sum2 = 0.0;
    for (int r = 0; r < runs; ++r) {
      WheelOdometryModel model(opt, 1000 + r);
      OdometrySample last;
      for (const auto& t : line) last = model.Step(t);
      sum += last.pose.theta;
      sum2 += last.pose.theta * last.pose.theta;
    }
    const double mean = sum / runs;
    const double var = sum2 / runs - mean * mean;
    const double expected = 2.0 * opt.wheel_noise_per_m * length / (0.4 * 0.4);
    EXPECT_NEAR(mean, 0.0, 4.0 * std::sqrt(expected / runs));
    EXPECT_NEAR(var / expected, 1.0, 0.25) << "length " << length;
  }
}

// The realistic level has the statistics it names: over many seeds, a 10 m straight run's
// distance is 1 % long with 2 % per metre of random error (sigma 0.02 sqrt(10) m) and its
// heading drifts 0.1 deg per metre; a full turn in place is reported 1 % large.
TEST(OdometryNoiseLevel, RealisticHasTheStatedStatistics) {
  WheelOdometryNoiseOptions opt;
  ASSERT_TRUE(SetOdometryNoiseLevel("realistic", &opt));
  EXPECT_EQ(opt.Validate(), "");
  const double length = 10.0;
  const auto line = StraightLine(length);
  std::vector<TruthSample> turn;
  for (int i = 0; i <= 628; ++i) turn.push_back({FromSeconds(i * 0.02), Pose2{0, 0, i * 0.01}});
  const int runs = 400;
  double d = 0, d2 = 0, h = 0, t = 0;
  for (int r = 0; r < runs; ++r) {
    WheelOdometryModel straight(opt, 500 + r);
    OdometrySample last;
    for (const auto& s : line) last = straight.Step(s);
    const double err = std::hypot(last.pose.x, last.pose.y) - length;
    d += err;
    d2 += err * err;
    h += last.pose.theta;
    WheelOdometryModel turning(opt, 5000 + r);
    double turned = 0.0;
    Pose2 previous = turn.front().pose;
    for (const auto& s : turn) {
      const Pose2 p = turning.Step(s).pose;
      turned += WrapAngle(p.theta - previous.theta);
      previous = p;
    }
    t += turned / 6.28;
  }
  const double mean = d / runs, sigma = std::sqrt(d2 / runs - mean * mean);
  EXPECT_NEAR(mean / length, 0.01, 0.0015);
  EXPECT_NEAR(sigma / (0.02 * std::sqrt(length)), 1.0, 0.1);
  EXPECT_NEAR((h / runs) * 180.0 / kPi / length, 0.1, 0.02);
  EXPECT_NEAR(t / runs, 1.01, 0.001);
}

TEST(OdometryNoiseLevel, DefaultIsTheDefaultsAndUnknownIsRefused) {
  WheelOdometryNoiseOptions opt;
  opt.track_width_m = 0.5;
  ASSERT_TRUE(SetOdometryNoiseLevel("realistic", &opt));
  EXPECT_EQ(opt.track_width_m, 0.5);
  EXPECT_NEAR((opt.right_scale_error - opt.left_scale_error) / 0.5, 0.1 * kPi / 180.0, 1e-12);
  ASSERT_TRUE(SetOdometryNoiseLevel("default", &opt));
  const WheelOdometryNoiseOptions defaults;
  EXPECT_EQ(opt.wheel_noise_per_m, defaults.wheel_noise_per_m);
  EXPECT_EQ(opt.left_scale_error, defaults.left_scale_error);
  EXPECT_EQ(opt.right_scale_error, defaults.right_scale_error);
  EXPECT_EQ(opt.track_width_error, defaults.track_width_error);
  EXPECT_EQ(opt.common_noise_per_m, 0.0);
  EXPECT_FALSE(SetOdometryNoiseLevel("awful", &opt));
}

}  // namespace
}  // namespace atlas
