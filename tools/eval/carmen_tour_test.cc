#include "tools/eval/carmen_tour.h"

#include <gtest/gtest.h>

#include <numbers>
#include <sstream>
#include <string>
#include <variant>

#include "logs/carmen/carmen_line.h"

namespace atlas::eval {
namespace {

carmen::CarmenEvent Odometry(double t, const Pose2& p) {
  carmen::CarmenEvent e;
  e.message = "ODOM";
  e.log_timestamp = t;
  e.event = OdometrySample{FromSeconds(t), p};
  return e;
}

// A scan of `beams` beams laid out as a FLASER line of that many beams is read.
carmen::CarmenEvent Scan(double t, int beams) {
  LaserScan s;
  s.stamp = FromSeconds(t);
  s.angle_min = static_cast<float>(-std::numbers::pi / 2.0);
  s.angle_increment = static_cast<float>(carmen::GuessFlaserAngleIncrement(beams));
  s.max_range = static_cast<float>(carmen::kFlaserMaxRange);
  s.sensor_pose = Pose2{0.12, 0.0, 0.0};
  for (int i = 0; i < beams; ++i) s.ranges.push_back(i % 7 == 3 ? kNoReturn : 1.0f + 0.01f * i);
  carmen::CarmenEvent e;
  e.message = "FLASER";
  e.log_timestamp = t;
  e.event = s;
  return e;
}

// 181 beams over 120 degrees.
carmen::CarmenEvent NotFlaser(double t) {
  carmen::CarmenEvent e = Scan(t, 181);
  auto& s = std::get<LaserScan>(e.event);
  s.angle_min = static_cast<float>(-std::numbers::pi / 3.0);
  s.angle_increment = static_cast<float>(2.0 * std::numbers::pi / 3.0 / 180.0);
  return e;
}

carmen::CarmenLog Read(const std::string& text) {
  carmen::CarmenLogBuilder b(carmen::CarmenLogOptions{}, "tour");
  std::istringstream in(text);
  int64_t n = 0;
  for (std::string line; std::getline(in, line);) EXPECT_TRUE(b.AddLine(++n, line)) << b.error();
  return b.Finish();
}

TEST(ContinueRun, StartsAGapAfterTheEndWhereTheOdometryEnded) {
  const std::vector<carmen::CarmenEvent> log = {Odometry(100.0, {5.0, 5.0, 1.0}), Scan(100.1, 181),
                                                Odometry(100.2, {5.3, 5.4, 1.2})};
  const OdometrySample end{FromSeconds(10.0), Pose2{1.0, 2.0, 0.5}};
  const std::vector<carmen::CarmenEvent> moved =
      ContinueRun(log, end, std::chrono::milliseconds(1000));
  ASSERT_EQ(moved.size(), 3u);
  const auto& first = std::get<OdometrySample>(moved[0].event);
  const auto& last = std::get<OdometrySample>(moved[2].event);
  EXPECT_EQ(first.stamp, FromSeconds(11.0));
  EXPECT_NEAR(moved[0].log_timestamp, 11.0, 1e-9);
  EXPECT_EQ(std::get<LaserScan>(moved[1].event).stamp, FromSeconds(11.1));
  EXPECT_EQ(last.stamp, FromSeconds(11.2));
  EXPECT_NEAR(first.pose.x, 1.0, 1e-12);
  EXPECT_NEAR(first.pose.y, 2.0, 1e-12);
  EXPECT_NEAR(first.pose.theta, 0.5, 1e-12);
  // The log's own motion is unchanged.
  const Pose2 was = Between(std::get<OdometrySample>(log[0].event).pose,
                            std::get<OdometrySample>(log[2].event).pose);
  const Pose2 is = Between(first.pose, last.pose);
  EXPECT_NEAR(is.x, was.x, 1e-12);
  EXPECT_NEAR(is.y, was.y, 1e-12);
  EXPECT_NEAR(is.theta, was.theta, 1e-12);
  EXPECT_TRUE(ContinueRun({}, end, std::chrono::seconds(1)).empty());
}

TEST(CarmenLines, ReadBackGiveTheSameScansAndOdometry) {
  const std::vector<carmen::CarmenEvent> events = {
      Scan(0.9, 181),  // before any odometry: left out
      Odometry(1.0, {0.0, 0.0, 0.0}),
      Scan(1.05, 181),
      Scan(1.06, 361),
      Odometry(1.1, {0.2, 0.1, 0.4}),
      NotFlaser(1.1),   // angles a FLASER line cannot state: left out
      Scan(1.2, 181)};  // after the last odometry: left out
  const CarmenLinesResult r = CarmenLines(events, "atlas-carmen");
  EXPECT_EQ(r.odometry_lines, 2);
  EXPECT_EQ(r.laser_lines, 2);
  EXPECT_EQ(r.scans_without_odometry, 2);
  EXPECT_EQ(r.scans_not_flaser, 1);
  EXPECT_NE(r.text.find(" atlas-carmen "), std::string::npos);
  const carmen::CarmenLog back = Read(r.text);
  ASSERT_EQ(back.laser_events, 2);
  ASSERT_EQ(back.odometry_events, 2);
  int scans = 0;
  for (const carmen::CarmenEvent& e : back.events) {
    const auto* s = std::get_if<LaserScan>(&e.event);
    if (s == nullptr) continue;
    const LaserScan& want = std::get<LaserScan>(events[scans == 0 ? 2 : 3].event);
    ++scans;
    EXPECT_EQ(s->stamp, want.stamp);
    EXPECT_FLOAT_EQ(s->angle_min, want.angle_min);
    EXPECT_FLOAT_EQ(s->angle_increment, want.angle_increment);
    EXPECT_NEAR(s->sensor_pose.x, want.sensor_pose.x, 1e-3);
    ASSERT_EQ(s->ranges.size(), want.ranges.size());
    for (size_t i = 0; i < want.ranges.size(); ++i) {
      EXPECT_EQ(IsReturn(s->ranges[i]), IsReturn(want.ranges[i])) << i;
      if (IsReturn(want.ranges[i])) {
        EXPECT_NEAR(s->ranges[i], want.ranges[i], 5e-4) << i;
      }
    }
  }
  EXPECT_EQ(scans, 2);
}

// Two logs as one run: the second goes on from the first's last odometry, in order.
TEST(CarmenLines, TwoLogsReadAsOneRun) {
  const std::vector<carmen::CarmenEvent> a = {Odometry(1.0, {0.0, 0.0, 0.0}), Scan(1.0, 181),
                                              Odometry(2.0, {3.0, 1.0, 0.5})};
  const std::vector<carmen::CarmenEvent> b = {Odometry(500.0, {-7.0, 2.0, 2.0}), Scan(500.0, 181),
                                              Odometry(501.0, {-6.0, 2.0, 2.0})};
  const carmen::CarmenLog first = Read(CarmenLines(a, "atlas-carmen").text);
  ASSERT_FALSE(first.events.empty());
  const auto end = std::get<OdometrySample>(first.events.back().event);
  const std::string text =
      CarmenLines(a, "atlas-carmen").text +
      CarmenLines(ContinueRun(b, end, std::chrono::seconds(1)), "atlas-carmen").text;
  const carmen::CarmenLog run = Read(text);
  EXPECT_EQ(run.out_of_order_lines, 0);
  EXPECT_EQ(run.laser_events, 2);
  ASSERT_EQ(run.odometry_events, 4);
  std::vector<OdometrySample> odometry;
  for (const carmen::CarmenEvent& e : run.events)
    if (const auto* o = std::get_if<OdometrySample>(&e.event)) odometry.push_back(*o);
  EXPECT_EQ(odometry[2].stamp, FromSeconds(3.0));
  EXPECT_NEAR(odometry[2].pose.x, 3.0, 1e-4);
  EXPECT_NEAR(odometry[2].pose.y, 1.0, 1e-4);
  EXPECT_NEAR(odometry[2].pose.theta, 0.5, 1e-4);
  const Pose2 was =
      Between(std::get<OdometrySample>(b[0].event).pose, std::get<OdometrySample>(b[2].event).pose);
  EXPECT_NEAR(Between(odometry[2].pose, odometry[3].pose).x, was.x, 1e-3);
  EXPECT_NEAR(Between(odometry[2].pose, odometry[3].pose).y, was.y, 1e-3);
}

// Where a run continues: the last ODOM line the reader takes, whatever follows it.
TEST(LastOdometryIn, FindsTheLastOdometryLine) {
  const std::vector<carmen::CarmenEvent> events = {Odometry(1.0, {0.0, 0.0, 0.0}), Scan(1.0, 181),
                                                   Odometry(2.0, {3.0, 1.0, 0.5}), Scan(2.0, 181)};
  const std::string text = CarmenLines(events, "atlas-carmen").text;
  const std::optional<OdometrySample> end = LastOdometryIn(text);
  ASSERT_TRUE(end.has_value());
  EXPECT_EQ(end->stamp, FromSeconds(2.0));
  EXPECT_NEAR(end->pose.x, 3.0, 1e-4);
  EXPECT_NEAR(end->pose.theta, 0.5, 1e-4);
  // A malformed last ODOM line is passed over; no ODOM line at all is none.
  EXPECT_EQ(LastOdometryIn(text + "ODOM 1 2\n")->stamp, FromSeconds(2.0));
  EXPECT_FALSE(LastOdometryIn(CarmenLines({Scan(1.0, 181)}, "atlas-carmen").text).has_value());
  EXPECT_FALSE(LastOdometryIn("").has_value());
}

}  // namespace
}  // namespace atlas::eval
