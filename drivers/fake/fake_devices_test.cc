#include <gtest/gtest.h>
#include <stdlib.h>
#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <thread>

#include "drivers/agilex/wheel_odometry.h"
#include "drivers/can/can_transport.h"
#include "drivers/device/laser_reader.h"
#include "drivers/device/sonar_reader.h"
#include "drivers/fake/fake_agilex_base.h"
#include "drivers/fake/fake_can_bus.h"
#include "drivers/fake/fake_lms.h"
#include "drivers/fake/fake_p2os.h"

namespace atlas::fake {
namespace {

std::string TempDir() {
  char t[] = "/tmp/atlas_fake_XXXXXX";
  return mkdtemp(t);
}

// The wheel counters the fake sends, integrated by the driver's integrator, give back an arc
// path through the same poses (to the counters' millimetre).
TEST(WheelPathEncoderTest, IntegratorRecoversArcPoses) {
  WheelPathEncoder enc(0.58);
  agilex::WheelOdometryOptions wo;
  wo.track_width_m = 0.58;
  agilex::WheelOdometryIntegrator integ(wo);
  Pose2 truth{2.0, -1.0, 0.3};
  enc.Reset(truth);
  Time t{};
  integ.Update(t, {0, 0});
  const Pose2 start = truth;
  for (int k = 0; k < 500; ++k) {
    // Drive arcs: forward 2 cm with a turn that changes sign, and some reversing.
    const double ds = (k % 100 < 80) ? 0.02 : -0.01;
    const double dth = 0.01 * std::sin(k * 0.05) + 0.0023;
    const double r = ds / dth;
    truth = Compose(truth, Pose2{r * std::sin(dth), r * (1 - std::cos(dth)), dth});
    t += std::chrono::milliseconds(20);
    ASSERT_EQ(integ.Update(t, enc.Advance(truth)), agilex::OdometryStep::kIntegrated);
  }
  const Pose2 want = Between(start, truth);
  const Pose2 have = integ.sample().pose;
  EXPECT_NEAR(have.x, want.x, 0.01);
  EXPECT_NEAR(have.y, want.y, 0.01);
  EXPECT_NEAR(WrapAngle(have.theta - want.theta), 0.0, 0.004);
}

TEST(FakeCanBusTest, FramesReachEveryClientAndAClosedBusIsGone) {
  const std::string dir = TempDir();
  const std::string path = dir + "/bus";
  FakeCanBus bus;
  std::string err;
  ASSERT_TRUE(bus.Listen(path, &err)) << err;
  auto a = MakeCanTransport("unix:" + path);
  auto b = MakeCanTransport("unix:" + path);
  ASSERT_TRUE(a->Open(&err)) << err;
  ASSERT_TRUE(b->Open(&err)) << err;
  EXPECT_EQ(bus.AcceptPending(), 2u);
  const CanFrame f = agilex::EncodeOdometry({1000, -2});
  EXPECT_EQ(bus.Broadcast(f), 2u);
  for (auto* t : {a.get(), b.get()}) {
    CanReadResult r = t->Read(500);
    ASSERT_EQ(r.status, CanRead::kFrame);
    EXPECT_EQ(r.frame, f);
  }
  bus.Close();
  EXPECT_EQ(a->Read(500).status, CanRead::kGone);
  a->Close();
  EXPECT_FALSE(a->Open(&err));  // nobody listening while the bus is down
  ASSERT_TRUE(bus.Listen(path, &err)) << err;
  EXPECT_TRUE(a->Open(&err)) << err;
  EXPECT_EQ(bus.AcceptPending(), 1u);
  bus.Close();
  std::filesystem::remove_all(dir);
}

TEST(SonarFromScanTest, NearestReturnInsideEachCone) {
  LaserScan scan;
  scan.angle_min = -M_PI / 2;
  scan.angle_increment = M_PI / 180;
  scan.ranges.assign(181, kNoReturn);
  scan.ranges[90] = 2.0f;   // straight ahead
  scan.ranges[92] = 1.5f;   // 2 deg left: same cone, nearer
  scan.ranges[180] = 0.7f;  // 90 deg left
  std::vector<SonarTransducer> ring(3);
  ring[0].pose = Pose2{0.1, 0, 0};
  ring[1].pose = Pose2{0, 0.1, M_PI / 2};
  ring[2].pose = Pose2{-0.1, 0, M_PI};  // behind: the laser does not see there
  const SonarReading r = SonarFromScan(scan, ring);
  ASSERT_EQ(r.returns.size(), 3u);
  EXPECT_FLOAT_EQ(r.returns[0].range, 1.5f);
  EXPECT_FLOAT_EQ(r.returns[1].range, 0.7f);
  EXPECT_FALSE(IsReturn(r.returns[2].range));
}

std::shared_ptr<Recording> TinyRecording(int scans = 50) {
  auto rec = std::make_shared<Recording>();
  for (int i = 0; i < scans; ++i) {
    LaserScan s;
    s.stamp = Time(std::chrono::milliseconds(100 * i));
    s.angle_min = -M_PI / 2;
    s.angle_increment = M_PI / 360;
    s.ranges.assign(361, 1.0f + 0.01f * i);
    s.ranges[7] = kNoReturn;
    rec->scans.push_back(s);
    rec->odometry.push_back({s.stamp, Pose2{0.05 * i, 0, 0}});
  }
  rec->begin = rec->scans.front().stamp;
  rec->end = rec->scans.back().stamp;
  return rec;
}

// A scanner left at 500000 baud by an earlier session: the driver finds nothing at 9600,
// finds it at 500000, and does not switch. The fake's record of the scans sent keeps the last 4
// of the 50 and counts all.
TEST(FakeLmsTest, ScannerStillAtHighRateIsFound) {
  const std::string dir = TempDir();
  auto rec = TinyRecording();
  auto clock = std::make_shared<PlaybackClock>(rec->begin, 10.0);
  FakeLmsOptions fo;
  fo.link = dir + "/laser";
  fo.power_up_baud = 500000;
  fo.sent_record_capacity = 4;
  FakeLms lms(fo, rec, clock);
  std::string err;
  ASSERT_TRUE(lms.Open(&err)) << err;
  lms.Start();
  LaserReaderOptions lo;
  lo.device = fo.link;
  LaserReader reader(lo);
  reader.Start();
  const Time deadline = Now() + std::chrono::seconds(5);
  while (!lms.streaming() && Now() < deadline)
    std::this_thread::sleep_for(std::chrono::milliseconds(5));
  ASSERT_TRUE(lms.streaming()) << reader.Health().last_error;
  EXPECT_EQ(reader.found_baud(), 500000);
  EXPECT_GE(lms.commands_ignored_wrong_rate(), 1u);  // the 9600 probe
  clock->Start();
  LaserScan s;
  int got = 0;
  while (!lms.finished() && Now() < deadline + std::chrono::seconds(5)) {
    while (reader.Pop(&s)) {
      EXPECT_EQ(s.ranges.size(), 361u);
      EXPECT_FALSE(IsReturn(s.ranges[7]));
      ++got;
    }
    std::this_thread::sleep_for(std::chrono::milliseconds(2));
  }
  std::this_thread::sleep_for(std::chrono::milliseconds(50));
  while (reader.Pop(&s)) ++got;
  EXPECT_EQ(got, 50);
  reader.Stop();
  lms.Stop();
  EXPECT_EQ(lms.sent_intact().total(), 50u);
  EXPECT_EQ(lms.sent_intact().Items(), (std::vector<size_t>{46, 47, 48, 49}));
  std::filesystem::remove_all(dir);
}

// The fake follows the baud switch: after 0x20 0x48 it answers only at 500000.
TEST(FakeLmsTest, BaudSwitchIsFollowed) {
  const std::string dir = TempDir();
  auto rec = TinyRecording();
  auto clock = std::make_shared<PlaybackClock>(rec->begin, 10.0);
  FakeLmsOptions fo;
  fo.link = dir + "/laser";
  FakeLms lms(fo, rec, clock);
  std::string err;
  ASSERT_TRUE(lms.Open(&err)) << err;
  lms.Start();
  LaserReaderOptions lo;
  lo.device = fo.link;
  lo.baud = 500000;
  LaserReader reader(lo);
  reader.Start();
  const Time deadline = Now() + std::chrono::seconds(5);
  while (!lms.streaming() && Now() < deadline)
    std::this_thread::sleep_for(std::chrono::milliseconds(5));
  EXPECT_TRUE(lms.streaming());
  EXPECT_EQ(reader.found_baud(), 9600);
  EXPECT_EQ(lms.baud(), 500000);
  EXPECT_EQ(lms.commands_answered(), 4u);  // status, baud, variant, continuous
  reader.Stop();
  lms.Stop();
  std::filesystem::remove_all(dir);
}

// AnswerLmsStartUp (for benchmarks that write the telegrams themselves): the reader's whole
// start-up, the switch to 500000 included, is answered on a pty the test owns; a telegram then
// written by hand arrives decoded, stamped after its write.
TEST(FakeLmsTest, StartUpAnsweredOnAnOwnPty) {
  PseudoTerminal pty;
  std::string err;
  ASSERT_TRUE(pty.Create("", &err)) << err;
  LaserReaderOptions lo;
  lo.device = pty.slave_path();
  lo.baud = 500000;
  lo.resolution_centideg = 100;  // 181 beams
  LaserReader reader(lo);
  reader.Start();
  ASSERT_TRUE(AnswerLmsStartUp(pty, std::chrono::seconds(5)));
  const Time deadline = Now() + std::chrono::seconds(5);
  while (reader.Health().state != DriverState::kRunning && Now() < deadline)
    std::this_thread::sleep_for(std::chrono::milliseconds(2));
  ASSERT_EQ(reader.Health().state, DriverState::kRunning) << reader.Health().last_error;
  EXPECT_EQ(pty.SlaveBaud(), 500000);
  LaserScan scan;
  scan.angle_min = -1.5707964f;
  scan.angle_increment = 0.017453292f;
  scan.ranges.assign(181, 2.5f);
  const std::vector<uint8_t> telegram =
      *sick::EncodeMeasuredValues(scan, sick::Unit::kMillimetre, 0x10);
  const Time written = Now();
  ASSERT_TRUE(pty.WriteAll(telegram.data(), telegram.size()));
  LaserScan out;
  while (!reader.Pop(&out) && Now() < deadline)
    std::this_thread::sleep_for(std::chrono::milliseconds(1));
  ASSERT_EQ(out.ranges.size(), 181u);
  EXPECT_NEAR(out.ranges[90], 2.5f, 1e-3f);
  EXPECT_GE(out.stamp, written);
  reader.Stop();
}

// A fake P2OS controller on a pseudo-terminal in a directory of its own, playing `recording`
// at `speed` times real time (its clock not started), and the options of a sonar reader on it.
// The controller is stopped and the directory removed at the end.
struct P2osBench {
  P2osBench(std::shared_ptr<const Recording> recording, double speed)
      : dir(TempDir()),
        clock(std::make_shared<PlaybackClock>(recording->begin, speed)),
        p2os(Options(dir), recording, clock) {}
  ~P2osBench() {
    p2os.Stop();
    std::filesystem::remove_all(dir);
  }
  static FakeP2osOptions Options(const std::string& dir) {
    FakeP2osOptions o;
    o.link = dir + "/sonar";
    return o;
  }
  SonarReaderOptions ReaderOptions() const {
    SonarReaderOptions so;
    so.device = Options(dir).link;
    so.sonar = Options(dir).sonar;
    return so;
  }
  const std::string dir;
  std::shared_ptr<PlaybackClock> clock;
  FakeP2os p2os;
};

// The sonar reader calls on_reading right after queueing each reading (atlasd's loop sleeps
// until then when its maps use the sonar): every reading sent arrives and was signalled.
TEST(FakeP2osTest, SonarReaderSignalsEveryQueuedReading) {
  P2osBench bench(TinyRecording(), 10.0);
  std::string err;
  ASSERT_TRUE(bench.p2os.Open(&err)) << err;
  bench.p2os.Start();
  FakeP2os& p2os = bench.p2os;
  auto& clock = bench.clock;
  std::atomic<int> signalled{0};
  SonarReaderOptions so = bench.ReaderOptions();
  so.on_reading = [&signalled] { signalled.fetch_add(1); };
  SonarReader reader(so);
  reader.Start();
  const Time deadline = Now() + std::chrono::seconds(5);
  while (!p2os.is_open() && Now() < deadline)
    std::this_thread::sleep_for(std::chrono::milliseconds(5));
  ASSERT_TRUE(p2os.is_open()) << reader.Health().last_error;
  clock->Start();
  SonarReading r;
  int got = 0;
  while (!p2os.finished() && Now() < deadline + std::chrono::seconds(5)) {
    while (reader.Pop(&r)) ++got;
    std::this_thread::sleep_for(std::chrono::milliseconds(2));
  }
  std::this_thread::sleep_for(std::chrono::milliseconds(50));
  reader.Stop();
  while (reader.Pop(&r)) ++got;
  EXPECT_GT(got, 10);
  EXPECT_EQ(got, static_cast<int>(p2os.sent_intact().total()));
  EXPECT_EQ(signalled.load(), got);
}

// The controller closes the connection when no PULSE comes for a second (devices.md, section
// 3); the reader's default keeps well inside that. Asserted on the intervals the fake saw,
// with room for a noisy machine: most of them (the median) are under 0.9 s. The old schedule
// (1 s period, sent on the next read turn) made every interval 1.0-1.1 s.
TEST(FakeP2osTest, PulsesComeMoreThanOnceASecond) {
  // 20 s of SIPs at real time: the line is never silent.
  P2osBench bench(TinyRecording(200), 1.0);
  std::string err;
  ASSERT_TRUE(bench.p2os.Open(&err)) << err;
  bench.p2os.Start();
  FakeP2os& p2os = bench.p2os;
  auto& clock = bench.clock;
  const SonarReaderOptions so = bench.ReaderOptions();
  ASSERT_EQ(so.Validate(), "");
  SonarReader reader(so);
  reader.Start();
  clock->Start();
  const Time deadline = Now() + std::chrono::seconds(15);
  SonarReading r;
  while (p2os.pulse_times().total() < 6 && Now() < deadline) {
    while (reader.Pop(&r)) {
    }
    std::this_thread::sleep_for(std::chrono::milliseconds(5));
  }
  reader.Stop();
  p2os.Stop();
  const std::vector<Time> t = p2os.pulse_times().Items();
  ASSERT_GE(t.size(), 6u) << reader.Health().last_error;
  std::vector<Duration> gaps;
  for (size_t k = 1; k < t.size(); ++k) gaps.push_back(t[k] - t[k - 1]);
  std::sort(gaps.begin(), gaps.end());
  const Duration median = gaps[gaps.size() / 2];
  EXPECT_LT(median, std::chrono::milliseconds(900)) << ToSeconds(median) << " s";
  EXPECT_LE(t.size(), reader.pulses_sent());
}

TEST(FaultOptionsTest, ADurationWithoutItsStartIsRefused) {
  FaultOptions f;
  EXPECT_EQ(f.Validate(), "");
  f.stall_for_s = 2;
  EXPECT_NE(f.Validate().find("stall_for_s without stall_after_s"), std::string::npos);
  f.stall_after_s = 1;
  EXPECT_EQ(f.Validate(), "");
  f.drop_for_s = 1;
  EXPECT_NE(f.Validate().find("drop_for_s without drop_after_s"), std::string::npos);
  f.drop_after_s = 0;
  EXPECT_EQ(f.Validate(), "");
  f.drop_after_s = std::nan("");
  EXPECT_NE(f.Validate().find("finite"), std::string::npos);
}

}  // namespace
}  // namespace atlas::fake
