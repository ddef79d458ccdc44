#include <gtest/gtest.h>

#include <thread>

#include "drivers/device/laser_reader.h"
#include "drivers/device/odometry_reader.h"
#include "drivers/device/sonar_reader.h"
#include "drivers/serial/pseudo_terminal.h"

namespace atlas {
namespace {

using std::chrono::milliseconds;

TEST(DeviceReaderTest, BackoffDoublesUpToTheCap) {
  ReconnectOptions o;
  o.initial_backoff = milliseconds(100);
  o.max_backoff = milliseconds(1000);
  EXPECT_EQ(BackoffDelay(o, 1), milliseconds(100));
  EXPECT_EQ(BackoffDelay(o, 2), milliseconds(200));
  EXPECT_EQ(BackoffDelay(o, 4), milliseconds(800));
  EXPECT_EQ(BackoffDelay(o, 5), milliseconds(1000));
  EXPECT_EQ(BackoffDelay(o, 1000), milliseconds(1000));
}

TEST(DeviceReaderTest, OptionsAreValidated) {
  ReconnectOptions r;
  EXPECT_EQ(r.Validate(), "");
  r.max_backoff = milliseconds(1);
  EXPECT_NE(r.Validate(), "");

  LaserReaderOptions l;
  EXPECT_NE(l.Validate().find("device path is empty"), std::string::npos);
  l.device = "/dev/ttyUSB0";
  EXPECT_EQ(l.Validate(), "");
  l.baud = 115200;
  EXPECT_NE(l.Validate().find("not an LMS rate"), std::string::npos);
  l.baud = 38400;
  l.resolution_centideg = 25;
  EXPECT_NE(l.Validate().find("100 deg range"), std::string::npos);
  l.resolution_centideg = 50;
  l.probe_rates = {500000, 9600};
  EXPECT_NE(l.Validate().find("start with 9600"), std::string::npos);

  OdometryReaderOptions o;
  EXPECT_EQ(o.Validate(), "");
  o.interface_name = "unix:";
  EXPECT_NE(o.Validate(), "");

  SonarReaderOptions s;
  s.device = "/dev/ttyS0";
  EXPECT_EQ(s.Validate(), "");
  s.pulse_period = std::chrono::seconds(3);
  EXPECT_NE(s.Validate().find("watchdog"), std::string::npos);
}

// A device that is not there: the reader keeps trying with backoff, says why, and stops
// promptly.
TEST(DeviceReaderTest, MissingDeviceIsRetriedAndReported) {
  LaserReaderOptions o;
  o.device = "/nonexistent/laser";
  o.reconnect.initial_backoff = milliseconds(5);
  o.reconnect.max_backoff = milliseconds(20);
  LaserReader r(o);
  r.Start();
  const Time deadline = Now() + std::chrono::seconds(5);
  while (r.Health().connect_failures < 5 && Now() < deadline)
    std::this_thread::sleep_for(milliseconds(5));
  const DriverHealth h = r.Health();
  EXPECT_GE(h.connect_failures, 5u);
  EXPECT_EQ(h.state, DriverState::kConnecting);
  EXPECT_NE(h.last_error.find("/nonexistent/laser"), std::string::npos) << h.last_error;
  EXPECT_NE(h.last_error.find("ENOENT"), std::string::npos) << h.last_error;
  r.Stop();
  EXPECT_EQ(r.Health().state, DriverState::kStopped);
}

TEST(DeviceReaderTest, GivesUpAfterTheAttemptBudget) {
  OdometryReaderOptions o;
  o.interface_name = "unix:/nonexistent/can";
  o.reconnect.initial_backoff = milliseconds(1);
  o.reconnect.max_backoff = milliseconds(2);
  o.reconnect.max_attempts = 3;
  OdometryReader r(o);
  r.Start();
  const Time deadline = Now() + std::chrono::seconds(5);
  while (r.Health().state != DriverState::kFailed && Now() < deadline)
    std::this_thread::sleep_for(milliseconds(2));
  EXPECT_EQ(r.Health().state, DriverState::kFailed);
  EXPECT_EQ(r.Health().connect_failures, 3u);
  EXPECT_NE(r.Health().last_error.find("nobody is listening"), std::string::npos);
}

// A line where nothing answers: the laser reader probes every rate and says so.
TEST(DeviceReaderTest, SilentLineNamesTheRatesTried) {
  PseudoTerminal pty;
  std::string err;
  ASSERT_TRUE(pty.Create("", &err)) << err;
  LaserReaderOptions o;
  o.device = pty.slave_path();
  o.reply_timeout = milliseconds(30);
  o.reconnect.initial_backoff = milliseconds(500);
  o.reconnect.max_backoff = milliseconds(500);
  LaserReader r(o);
  r.Start();
  const Time deadline = Now() + std::chrono::seconds(5);
  while (r.Health().connect_failures < 1 && Now() < deadline)
    std::this_thread::sleep_for(milliseconds(5));
  const std::string e = r.Health().last_error;
  EXPECT_NE(e.find("no answer to the status request at 9600, 500000, 38400, 19200 baud"),
            std::string::npos)
      << e;
  // It did probe at every rate: the last one it set on the line is the last probe rate.
  EXPECT_EQ(pty.SlaveBaud(), 19200);
  r.Stop();
}

TEST(DeviceReaderTest, StateNames) {
  EXPECT_STREQ(ToString(DriverState::kRunning), "running");
  EXPECT_STREQ(ToString(DriverState::kReconnecting), "reconnecting");
  EXPECT_STREQ(ToString(DriverState::kStalled), "stalled");
}

}  // namespace
}  // namespace atlas
