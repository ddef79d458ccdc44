#include "daemon/lcm_in/lcm_input.h"

#include <gtest/gtest.h>

#include <chrono>
#include <thread>

#include "daemon/lcm_out/lcm_convert.h"

namespace atlas {
namespace {

// Waits up to 2 s for `done`.
template <typename F>
bool Eventually(F done) {
  for (int i = 0; i < 400; ++i) {
    if (done()) return true;
    std::this_thread::sleep_for(std::chrono::milliseconds(5));
  }
  return done();
}

class LcmInputTest : public ::testing::Test {
 protected:
  // A memq:// instance: what the test publishes on it, the input's thread handles.
  void StartInput(LcmInputOptions o) {
    o.url = "memq://";
    auto lcm = std::make_unique<lcm::LCM>("memq://");
    bus_ = lcm.get();
    input_ = std::make_unique<LcmInput>(o, std::move(lcm));
    std::string error;
    ASSERT_TRUE(input_->Start(&error)) << error;
  }
  lcm::LCM* bus_ = nullptr;
  std::unique_ptr<LcmInput> input_;
};

TEST_F(LcmInputTest, QueuesPlainStructsStampedAtArrival) {
  int woken = 0;
  LcmInputOptions o;
  o.laser_type = LaserMessageType::kPlanarLidar;
  o.odometry_type = OdometryMessageType::kBotPose;
  o.laser_channel = "SCAN";
  o.odometry_channel = "POSE";
  o.laser = LaserSetup{Pose2{0.2, 0, 0}, 10.0f};
  o.on_scan = [&woken] { ++woken; };
  StartInput(o);
  EXPECT_EQ(input_->LaserHealth().state, DriverState::kRunning);
  EXPECT_NE(input_->LaserHealth().device.find("SCAN"), std::string::npos);

  const Time before = Now();
  bot_core::pose_t pose{};
  pose.utime = 1796166934722075;
  pose.pos[0] = 2.0;
  pose.orientation[0] = 1.0;
  bus_->publish("POSE", &pose);
  bot_core::planar_lidar_t scan{};
  scan.utime = 1796166934722075;
  scan.nranges = 3;
  scan.ranges = {1.0f, 2.0f, 3.0f};
  scan.radstep = 0.5f;
  bus_->publish("SCAN", &scan);

  OdometrySample s;
  ASSERT_TRUE(Eventually([&] { return input_->odometry_queue().Pop(&s); }));
  EXPECT_EQ(s.pose.x, 2.0);
  EXPECT_GE(s.stamp, before);
  EXPECT_LE(s.stamp, Now());
  LaserScan l;
  ASSERT_TRUE(Eventually([&] { return input_->laser_queue().Pop(&l); }));
  EXPECT_EQ(l.ranges.size(), 3u);
  EXPECT_EQ(l.sensor_pose.x, 0.2);
  EXPECT_GE(l.stamp, s.stamp);
  EXPECT_EQ(woken, 1);
  const DriverHealth h = input_->LaserHealth();
  EXPECT_EQ(h.messages, 1u);
  EXPECT_EQ(h.samples, 1u);
  EXPECT_GT(h.bytes, 0u);
}

TEST_F(LcmInputTest, BadMessagesAreCountedWithTheirReasonAndTheInputGoesOn) {
  LcmInputOptions o;
  o.laser_enabled = false;
  StartInput(o);
  EXPECT_EQ(input_->LaserHealth().state, DriverState::kStopped);  // not subscribed
  bot_core::pose_t wrong{};
  bus_->publish("ATLAS_RAW_ODOMETRY", &wrong);
  const uint8_t garbage[3] = {1, 2, 3};
  bus_->publish("ATLAS_RAW_ODOMETRY", garbage, sizeof garbage);
  atlasd::odometry_t right{};
  right.x = 1.0;
  bus_->publish("ATLAS_RAW_ODOMETRY", &right);
  OdometrySample s;
  ASSERT_TRUE(Eventually([&] { return input_->odometry_queue().Pop(&s); }));
  EXPECT_EQ(s.pose.x, 1.0);
  const DriverHealth h = input_->OdometryHealth();
  EXPECT_EQ(h.bad_messages, 2u);
  EXPECT_EQ(h.messages, 1u);
  EXPECT_NE(h.last_error.find("not a atlasd.odometry_t"), std::string::npos) << h.last_error;
  EXPECT_EQ(h.state, DriverState::kRunning);
}

TEST_F(LcmInputTest, SilenceIsStaleWithAReasonUntilTheNextMessage) {
  LcmInputOptions o;
  o.laser_enabled = false;
  o.stall_timeout = std::chrono::milliseconds(100);
  std::vector<std::string> said;
  o.log = [&said](const DriverLogLine& l) { said.push_back(l.text); };
  StartInput(o);
  ASSERT_TRUE(Eventually([&] { return input_->OdometryHealth().state == DriverState::kStalled; }));
  DriverHealth h = input_->OdometryHealth();
  EXPECT_EQ(h.stalls, 1u);
  EXPECT_NE(h.last_error.find("no message on ATLAS_RAW_ODOMETRY"), std::string::npos)
      << h.last_error;
  atlasd::odometry_t m{};
  bus_->publish("ATLAS_RAW_ODOMETRY", &m);
  ASSERT_TRUE(Eventually([&] { return input_->OdometryHealth().state == DriverState::kRunning; }));
  input_->Stop();
  EXPECT_EQ(input_->OdometryHealth().state, DriverState::kStopped);
  bool stalled_said = false;
  for (const std::string& line : said)
    stalled_said = stalled_said || line.find("no message on") != std::string::npos;
  EXPECT_TRUE(stalled_said);
}

TEST_F(LcmInputTest, AFullQueueDropsTheOldestAndCountsIt) {
  LcmInputOptions o;
  o.laser_enabled = false;
  o.odometry_queue_capacity = 2;
  StartInput(o);
  for (int i = 0; i < 5; ++i) {
    atlasd::odometry_t m{};
    m.x = i;
    bus_->publish("ATLAS_RAW_ODOMETRY", &m);
  }
  ASSERT_TRUE(Eventually([&] { return input_->OdometryHealth().messages == 5; }));
  EXPECT_EQ(input_->OdometryHealth().drops, 3u);
  OdometrySample s;
  ASSERT_TRUE(input_->odometry_queue().Pop(&s));
  EXPECT_EQ(s.pose.x, 3.0);
}

TEST(LcmInputOptionsTest, ValidateNamesWhatIsWrong) {
  LcmInputOptions o;
  o.url = "memq://";
  EXPECT_EQ(o.Validate(), "");
  o.odometry_channel = o.laser_channel;
  EXPECT_NE(o.Validate().find("same"), std::string::npos);
  o.laser_enabled = false;
  EXPECT_EQ(o.Validate(), "");
  o.odometry_queue_capacity = 0;
  EXPECT_NE(o.Validate(), "");
}

}  // namespace
}  // namespace atlas
