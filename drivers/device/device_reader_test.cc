#include <gtest/gtest.h>
#include <stdlib.h>

#include <filesystem>
#include <mutex>
#include <new>
#include <thread>
#include <vector>

#include "drivers/agilex/agilex_messages.h"
#include "drivers/device/gap_resync.h"
#include "drivers/device/laser_reader.h"
#include "drivers/device/odometry_reader.h"
#include "drivers/device/sonar_reader.h"
#include "drivers/fake/fake_can_bus.h"
#include "drivers/serial/pseudo_terminal.h"
#include "drivers/serial/serial_port.h"
#include "drivers/sick/lms_messages.h"
#include "drivers/sick/lms_telegram.h"

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
  o.interface_name = "can0";
  o.odometry.max_gap_s = -1;
  EXPECT_NE(o.Validate().find("max_gap_s"), std::string::npos);

  SonarReaderOptions s;
  s.device = "/dev/ttyS0";
  EXPECT_EQ(s.Validate(), "");
  s.pulse_period = std::chrono::seconds(3);
  EXPECT_NE(s.Validate().find("watchdog"), std::string::npos);
  // A 1 s period is sent on the next read turn, after the second is up.
  s.pulse_period = std::chrono::seconds(1);
  EXPECT_NE(s.Validate().find("watchdog"), std::string::npos);
  s.pulse_period = std::chrono::milliseconds(850);
  s.truncation_gap = std::chrono::milliseconds(200);
  EXPECT_NE(s.Validate().find("watchdog"), std::string::npos);
  s.truncation_gap = std::chrono::milliseconds(100);
  EXPECT_EQ(s.Validate(), "");
}

// A device that opens and dies at once (SocketCAN on a down interface: bind succeeds, the
// first read gives ENETDOWN), except in session `deliver_in`, which decodes one message. The
// backoff delays the reader asks for are recorded instead of slept (nothing here is timed).
class FlappingDevice final : public DeviceReader {
 public:
  FlappingDevice(const ReconnectOptions& o, int deliver_in)
      : DeviceReader("flapping", o), deliver_in_(deliver_in) {}
  ~FlappingDevice() override { Stop(); }
  std::vector<Duration> delays() const {
    std::lock_guard<std::mutex> lock(mutex_);
    return delays_;
  }

 protected:
  bool Connect(std::string*) override {
    ++sessions_;
    return true;
  }
  SessionEnd ReadUntilGone(std::string* error) override {
    if (sessions_ == deliver_in_) health_.CountMessage(Now());
    *error = "CAN can0: interface is down (ENETDOWN)";
    return SessionEnd::kGone;
  }
  void Disconnect() override {}
  uint64_t QueueDrops() const override { return 0; }
  bool BackoffSleep(Duration d) override {
    std::unique_lock<std::mutex> lock(mutex_);
    delays_.push_back(d);
    const bool enough = delays_.size() >= 8;
    lock.unlock();
    return enough ? SleepFor(std::chrono::hours(1)) : !Stopping();  // Stop() interrupts
  }

 private:
  const int deliver_in_;
  int sessions_ = 0;
  mutable std::mutex mutex_;
  std::vector<Duration> delays_;
};

TEST(DeviceReaderTest, BackoffGrowsWhileSessionsBringNoData) {
  ReconnectOptions o;
  o.initial_backoff = milliseconds(5);
  o.max_backoff = milliseconds(80);
  FlappingDevice d(o, /*deliver_in=*/4);
  d.Start();
  const Time deadline = Now() + std::chrono::seconds(5);
  while (d.delays().size() < 8 && Now() < deadline) std::this_thread::sleep_for(milliseconds(1));
  d.Stop();
  // The first three sessions bring nothing: 5, 10, 20 ms; the fourth decodes a message, so the
  // count starts again: 5; then 10, 20, 40 and the cap, 80.
  const std::vector<Duration> want = {milliseconds(5),  milliseconds(10), milliseconds(20),
                                      milliseconds(5),  milliseconds(10), milliseconds(20),
                                      milliseconds(40), milliseconds(80)};
  EXPECT_EQ(d.delays(), want);
  const DriverHealth h = d.Health();
  EXPECT_EQ(h.connect_failures, 0u);
  EXPECT_EQ(h.disconnects, 8u);
  EXPECT_EQ(h.messages, 1u);
}

// The lines a reader says, collected from its thread.
class LogLines {
 public:
  DriverLogSink Sink() {
    return [this](const DriverLogLine& l) {
      std::lock_guard<std::mutex> lock(mutex_);
      lines_.push_back(l);
    };
  }
  std::vector<DriverLogLine> lines() const {
    std::lock_guard<std::mutex> lock(mutex_);
    return lines_;
  }

 private:
  mutable std::mutex mutex_;
  std::vector<DriverLogLine> lines_;
};

TEST(DeviceReaderTest, AFlappingDeviceSaysEachChangeOnceNotEachRetry) {
  LogLines log;
  ReconnectOptions o;
  o.initial_backoff = milliseconds(5);
  o.max_backoff = milliseconds(80);
  o.log = log.Sink();
  FlappingDevice d(o, /*deliver_in=*/4);
  d.Start();
  const Time deadline = Now() + std::chrono::seconds(5);
  while (d.delays().size() < 8 && Now() < deadline) std::this_thread::sleep_for(milliseconds(1));
  d.Stop();
  const std::string down = "CAN can0: interface is down (ENETDOWN)";
  const std::vector<DriverLogLine> want = {
      {LogPriority::kInfo, "flapping: connecting"},
      {LogPriority::kErr, "flapping: " + down + "; retrying"},
      {LogPriority::kNotice, "flapping: running after 3 failed attempts"},
      {LogPriority::kWarning, "flapping: lost (" + down + "); reconnecting"},
      {LogPriority::kErr, "flapping: " + down + "; retrying"},
      {LogPriority::kInfo, "flapping: stopped"},
  };
  EXPECT_EQ(log.lines(), want);
}

// A session that throws (what is left once no input can: out of memory) stops that reader,
// said in its health, and leaves the process running.
class ThrowingDevice final : public DeviceReader {
 public:
  ThrowingDevice() : DeviceReader("throwing", ReconnectOptions{}) {}
  ~ThrowingDevice() override { Stop(); }

 protected:
  bool Connect(std::string*) override { return true; }
  SessionEnd ReadUntilGone(std::string*) override { throw std::bad_alloc(); }
  void Disconnect() override {}
  uint64_t QueueDrops() const override { return 0; }
};

TEST(DeviceReaderTest, AnExceptionStopsOnlyThatReaderAndSaysSo) {
  ThrowingDevice d;
  d.Start();
  const Time deadline = Now() + std::chrono::seconds(5);
  while (d.Health().state != DriverState::kFailed && Now() < deadline)
    std::this_thread::sleep_for(milliseconds(1));
  const DriverHealth h = d.Health();
  EXPECT_EQ(h.state, DriverState::kFailed);
  EXPECT_NE(h.last_error.find("the reader stopped"), std::string::npos) << h.last_error;
  EXPECT_NE(h.last_error.find("bad_alloc"), std::string::npos) << h.last_error;
  d.Stop();
}

// A device that is not there: the reader keeps trying with backoff, says why, and stops
// promptly.
TEST(DeviceReaderTest, MissingDeviceIsRetriedAndReported) {
  LogLines log;
  LaserReaderOptions o;
  o.reconnect.log = log.Sink();
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
  // Said once with its reason, not once per retry.
  const std::vector<DriverLogLine> lines = log.lines();
  ASSERT_EQ(lines.size(), 3u);
  EXPECT_EQ(lines[1].priority, LogPriority::kErr);
  EXPECT_NE(lines[1].text.find("ENOENT"), std::string::npos) << lines[1].text;
  EXPECT_EQ(lines[2].text, "laser /nonexistent/laser: stopped");
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

// Waits (up to 5 s) until `done` holds.
template <typename Done>
bool WaitFor(Done&& done) {
  const Time deadline = Now() + std::chrono::seconds(5);
  while (!done() && Now() < deadline) std::this_thread::sleep_for(milliseconds(2));
  return done();
}

// A base reboot seen by the reader: the bus goes away, comes back, and the counters start again
// near zero. The reset (137 mm back) would be plausible motion over the reconnect's gap; the
// re-reference on the reconnect skips it as one discontinuity and the pose goes on.
TEST(DeviceReaderTest, OdometryReconnectReReferencesTheCounters) {
  char tmp[] = "/tmp/atlas_odo_XXXXXX";
  const std::string dir = mkdtemp(tmp);
  const std::string path = dir + "/bus";
  fake::FakeCanBus bus;
  std::string err;
  ASSERT_TRUE(bus.Listen(path, &err)) << err;
  OdometryReaderOptions o;
  o.interface_name = "unix:" + path;
  o.reconnect.initial_backoff = milliseconds(100);
  o.reconnect.max_backoff = milliseconds(200);
  OdometryReader r(o);
  r.Start();
  ASSERT_TRUE(WaitFor([&] { return bus.AcceptPending() >= 1; }));
  OdometrySample s, last;
  int got = 0;
  auto pop_until = [&](int n) {
    return WaitFor([&] {
      while (r.Pop(&s)) {
        last = s;
        ++got;
      }
      return got >= n;
    });
  };
  bus.Broadcast(agilex::EncodeMotionState({500, -250}));
  for (int mm : {120, 130, 140}) bus.Broadcast(agilex::EncodeOdometry({mm, mm}));
  ASSERT_TRUE(pop_until(3)) << got;  // the first frame is the reference, at the origin
  EXPECT_NEAR(last.pose.x, 0.02, 1e-9);
  // The raw sample carries what the base reported: counters and velocities.
  EXPECT_EQ(last.left_m, 0.14);
  EXPECT_EQ(last.right_m, 0.14);
  EXPECT_EQ(last.linear_velocity, 0.5);
  EXPECT_EQ(last.angular_velocity, -0.25);
  bus.Close();
  ASSERT_TRUE(WaitFor([&] { return r.Health().disconnects >= 1; }));
  ASSERT_TRUE(bus.Listen(path, &err)) << err;
  ASSERT_TRUE(WaitFor([&] { return bus.AcceptPending() >= 1; }));
  for (int mm : {3, 13}) bus.Broadcast(agilex::EncodeOdometry({mm, mm}));
  ASSERT_TRUE(pop_until(5)) << got;  // the new reference is a sample at the kept pose
  EXPECT_NEAR(last.pose.x, 0.03, 1e-9);
  const DriverHealth h = r.Health();
  EXPECT_EQ(h.discontinuities, 1u);
  EXPECT_EQ(h.reconnects, 1u);
  EXPECT_NE(h.last_error.find("reconnected"), std::string::npos) << h.last_error;
  r.Stop();
  bus.Close();
  std::filesystem::remove_all(dir);
}

// A scanner still streaming from an earlier session answers the start-up status request after
// two scans, all in one burst of bytes. The scans are stamped with the arrival of that burst,
// not with the time each is processed: on_scan takes 30 ms, yet both carry the same stamp,
// taken before the first was handed on.
TEST(DeviceReaderTest, ScansDuringStartUpAreStampedAtArrival) {
  PseudoTerminal pty;
  std::string err;
  ASSERT_TRUE(pty.Create("", &err)) << err;
  std::mutex mutex;
  Time first_handed_on{};
  LaserReaderOptions o;
  o.device = pty.slave_path();
  o.baud = 9600;
  o.reply_timeout = milliseconds(300);
  o.on_scan = [&] {
    {
      std::lock_guard<std::mutex> lock(mutex);
      if (first_handed_on == Time{}) first_handed_on = Now();
    }
    std::this_thread::sleep_for(milliseconds(30));
  };
  LaserReader r(o);
  r.Start();
  // The status request, 02 00 01 00 31 15 12.
  const std::vector<uint8_t> request = sick::EncodeStatusRequest();
  std::vector<uint8_t> got;
  uint8_t buf[64];
  const Time deadline = Now() + std::chrono::seconds(5);
  while (got.size() < request.size() && Now() < deadline) {
    const long n = pty.Read(buf, sizeof(buf), 50);
    if (n > 0) got.insert(got.end(), buf, buf + n);
  }
  ASSERT_EQ(got, request);
  LaserScan scan;
  scan.ranges.assign(181, 2.0f);
  std::vector<uint8_t> burst;
  for (int k = 0; k < 2; ++k) {
    const auto b0 = sick::EncodeMeasuredValues(scan, sick::Unit::kMillimetre, 0x10);
    ASSERT_TRUE(b0.has_value());
    burst.insert(burst.end(), b0->begin(), b0->end());
  }
  const std::vector<uint8_t> status = sick::EncodeStatusReply(0x10);
  burst.insert(burst.end(), status.begin(), status.end());
  ASSERT_LT(burst.size(), 1024u);  // one read of the reader's start-up buffer
  const Time written = Now();
  ASSERT_TRUE(pty.WriteAll(burst.data(), burst.size()));
  std::vector<LaserScan> scans;
  while (scans.size() < 2 && Now() < deadline) {
    LaserScan s;
    while (r.Pop(&s)) scans.push_back(std::move(s));
    std::this_thread::sleep_for(milliseconds(2));
  }
  r.Stop();
  ASSERT_EQ(scans.size(), 2u);
  EXPECT_EQ(scans[0].stamp, scans[1].stamp);
  EXPECT_GE(scans[0].stamp, written);
  std::lock_guard<std::mutex> lock(mutex);
  EXPECT_LE(scans[1].stamp, first_handed_on);
}

// A serial session as the laser reader runs it (ReadSerialUntilGone with the LMS decoder),
// recording the arrival stamp of every telegram.
class LmsSession final : public DeviceReader {
 public:
  LmsSession(std::string path, Duration gap)
      : DeviceReader("lms session", ReconnectOptions{}), path_(std::move(path)), gap_(gap) {}
  ~LmsSession() override { Stop(); }
  std::vector<Time> stamps() const {
    std::lock_guard<std::mutex> lock(mutex_);
    return stamps_;
  }

 protected:
  bool Connect(std::string* error) override { return port_.Open({path_, 9600, true}, error); }
  SessionEnd ReadUntilGone(std::string* error) override {
    return ReadSerialUntilGone(
        port_, decoder_, resync_, gap_,
        [&](const sick::StreamEvent& e, Time arrival) {
          if (e.kind != sick::StreamEventKind::kTelegram) return;
          std::lock_guard<std::mutex> lock(mutex_);
          stamps_.push_back(arrival);
        },
        [] { return true; }, [] {}, "lms session", "reopening", error);
  }
  void Disconnect() override { port_.Close(); }
  uint64_t QueueDrops() const override { return 0; }

 private:
  const std::string path_;
  const Duration gap_;
  SerialPort port_;
  sick::StreamDecoder decoder_;
  GapResync<sick::StreamDecoder::kWindow> resync_;
  mutable std::mutex mutex_;
  std::vector<Time> stamps_;
};

// A false STX that announces a long telegram holds the real one until the line has been silent
// for the truncation gap; the telegram found then was already there: it is stamped with the
// arrival of its bytes, not with the end of the gap (2 s here).
TEST(DeviceReaderTest, ATelegramFoundAfterAFalseStxKeepsItsArrivalStamp) {
  PseudoTerminal pty;
  std::string err;
  ASSERT_TRUE(pty.Create("", &err)) << err;
  LmsSession session(pty.slave_path(), std::chrono::seconds(2));
  session.Start();
  const Time deadline = Now() + std::chrono::seconds(10);
  while (session.Health().state != DriverState::kRunning && Now() < deadline)
    std::this_thread::sleep_for(milliseconds(2));
  ASSERT_EQ(session.Health().state, DriverState::kRunning);
  std::vector<uint8_t> bytes = {0x02, 0x80, 0x00, 0x03};  // STX, address, LEN 768
  const std::vector<uint8_t> status = sick::EncodeStatusReply(0x10);
  bytes.insert(bytes.end(), status.begin(), status.end());
  const Time written = Now();
  ASSERT_TRUE(pty.WriteAll(bytes.data(), bytes.size()));
  while (session.stamps().empty() && Now() < deadline) std::this_thread::sleep_for(milliseconds(5));
  session.Stop();
  const std::vector<Time> stamps = session.stamps();
  ASSERT_EQ(stamps.size(), 1u);
  EXPECT_GE(stamps[0], written);
  EXPECT_LT(ToSeconds(stamps[0] - written), 1.0) << "stamped at the end of the 2 s gap";
  EXPECT_EQ(session.Health().truncated, 1u);
}

TEST(DeviceReaderTest, StateNames) {
  EXPECT_STREQ(ToString(DriverState::kRunning), "running");
  EXPECT_STREQ(ToString(DriverState::kReconnecting), "reconnecting");
  EXPECT_STREQ(ToString(DriverState::kStalled), "stalled");
}

}  // namespace
}  // namespace atlas
