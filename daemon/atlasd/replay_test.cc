#include "daemon/atlasd/replay.h"

#include <gtest/gtest.h>
#include <stdlib.h>

#include <cerrno>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <lcm/lcm-cpp.hpp>
#include <random>
#include <sstream>
#include <string>
#include <vector>

#include "core/testing/fake_sonar_ring.h"
#include "core/testing/fake_step_sink.h"
#include "core/testing/fake_wall_scanner.h"
#include "daemon/atlasd/daemon_setup.h"
#include "daemon/atlasd/input_drain.h"
#include "daemon/lcm_out/atlas_publisher.h"
#include "formats/replay_dir.h"
#include "formats/text_rows.h"
#include "formats/trajectory_tsv.h"

namespace atlas {
namespace {

struct Row {
  Time stamp;
  DominantOutput pose;
};

// The poses of steps (not of dead reckoning).
std::vector<Row> Steps(const FakeStepSink& sink) {
  std::vector<Row> rows;
  for (const RecordedPose& p : sink.poses)
    if (p.source == PoseSource::kScan) rows.push_back({p.stamp, p.pose});
  return rows;
}

// What lcm-logger does: every message of the LCM instance into an lcm-logger file.
class LogRecorder {
 public:
  LogRecorder(lcm::LCM* lcm, const std::string& path) : log_(path, "w") {
    lcm->subscribe(".*", &LogRecorder::On, this);
  }
  bool good() const { return log_.good(); }
  void On(const lcm::ReceiveBuffer* rb, const std::string& channel) {
    lcm::LogEvent e;
    e.eventnum = events_++;
    e.timestamp = rb->recv_utime;
    e.channel = channel;
    e.datalen = static_cast<int32_t>(rb->data_size);
    e.data = rb->data;
    log_.writeEvent(&e);
  }

 private:
  lcm::LogFile log_;
  int64_t events_ = 0;
};

struct LiveRun {
  std::vector<Row> rows;
  int scans = 0, readings = 0;
  int late_items = 0;  // items the maps use, added right after a newer one
};

// What the live loop thread does with a drain (loop_thread.h): every item republished raw on
// LCM, and added to the loop when the maps use it; counts the items added after a newer one.
class LiveDrainTarget final : public DrainTarget {
 public:
  LiveDrainTarget(AtlasPublisher* publisher, StepLoop* loop, const DaemonOptions& o, LiveRun* run)
      : publisher_(publisher),
        loop_(loop),
        use_laser_(o.localmap.sensors != RangeSensors::kSonar),
        use_sonar_(o.localmap.sensors != RangeSensors::kLaser),
        run_(run) {}
  void OnOdometry(const OdometrySample& s) override {
    publisher_->RawOdometry(s);
    loop_->AddOdometry(s);
  }
  void OnSonar(SonarReading& r) override {
    publisher_->RawSonar(r);
    if (!use_sonar_) return;
    Added(r.stamp);
    loop_->AddSonar(std::move(r));
  }
  void OnScan(LaserScan& s) override {
    publisher_->RawLaser(s);
    if (!use_laser_) return;
    Added(s.stamp);
    loop_->AddScan(std::move(s));
  }

 private:
  void Added(Time stamp) {
    if (stamp < last_added_) ++run_->late_items;
    last_added_ = stamp;
  }
  AtlasPublisher* publisher_;
  StepLoop* loop_;
  bool use_laser_, use_sonar_;
  LiveRun* run_;
  Time last_added_{};
};

// A robot driving 3 m down a corridor (walls at y = +-1.2, an end wall), odometry at 50 Hz, the
// laser (181 beams) at 25 Hz and the sonar ring at 10 Hz, through the live loop's order of work
// (loop_thread.h): a wake-up drains the queues with the live loop's InputDrain (the odometry,
// then the readings and scans in stamp order, each republished raw on memq:// LCM, recorded
// into `log_path` as lcm-logger does, and added if the maps use it), then steps one item, and
// steps on (or, at random, takes the next arrivals first, as a loaded loop does). One scan in
// five reaches its queue 20 ms after its arrival stamp (a reader preempted before its push), so
// that a newer reading may be drained, and stepped or still pending, before it.
LiveRun RunLive(const DaemonOptions& o, const std::string& log_path, uint64_t seed,
                const EpochClock& epoch) {
  LiveRun run;
  lcm::LCM lcm("memq://");
  EXPECT_TRUE(lcm.good());
  LogRecorder logger(&lcm, log_path);
  EXPECT_TRUE(logger.good());
  AtlasPublisher publisher(&lcm, o.lcm.channels, epoch);
  const MapperSettings settings = ToMapperSettings(o);
  std::unique_ptr<Atlas> atlas = MakeAtlas(settings);
  StepLoop loop(ToStepLoopOptions(o), settings, atlas.get());
  FakeStepSink sink;
  const std::vector<sim::Wall> walls = {{Vec2(-5, 1.2), Vec2(30, 1.2)},
                                        {Vec2(-5, -1.2), Vec2(30, -1.2)},
                                        {Vec2(9, -1.2), Vec2(9, 1.2)}};
  FakeLaserOptions laser_options;
  laser_options.beams = 181;
  FakeWallScanner laser(walls, laser_options, seed);
  std::mt19937_64 rng(seed);
  std::bernoulli_distribution wakes(0.5), catches_up(0.3), late(0.2);
  SpscQueue<OdometrySample> odometry_queue(64);
  SpscQueue<SonarReading> sonar_queue(64);
  SpscQueue<LaserScan> laser_queue(64);
  std::vector<std::pair<int, LaserScan>> laser_in_flight;  // (tick of the push, scan)
  InputDrain input(&odometry_queue, &sonar_queue, &laser_queue);
  LiveDrainTarget target(&publisher, &loop, o, &run);
  auto drain = [&] {
    input.Drain(&target);
    while (lcm.handleTimeout(0) > 0) {
    }
  };
  for (int k = 0; k <= 600; ++k) {  // 10 ms ticks
    const double t = 0.01 * k;
    const Pose2 robot{0.5 * t, 0.0, 0.0};
    if (k % 2 == 0) odometry_queue.Push({FromSeconds(t), robot});
    if (k % 10 == 3) {
      SonarReading reading = FireFakeSonarRing(walls, settings.sonar_ring, robot, 0.01, rng);
      reading.stamp = FromSeconds(t);
      sonar_queue.Push(std::move(reading));
      ++run.readings;
    }
    if (k % 4 == 2) {
      laser_in_flight.emplace_back(k + (late(rng) ? 2 : 0), laser.Scan(robot));
      laser_in_flight.back().second.stamp = FromSeconds(t);
      ++run.scans;
    }
    while (!laser_in_flight.empty() && laser_in_flight.front().first <= k) {
      laser_queue.Push(std::move(laser_in_flight.front().second));
      laser_in_flight.erase(laser_in_flight.begin());
    }
    if (!wakes(rng)) continue;
    drain();
    loop.StepOne(&sink);
    if (catches_up(rng)) loop.StepAll(&sink);
  }
  drain();
  loop.StepAll(&sink);
  EXPECT_EQ(loop.dropped_scans(), 0);
  EXPECT_EQ(loop.dropped_sonar(), 0);
  run.rows = Steps(sink);
  return run;
}

// The replay's trajectory.tsv (the steps with a dominant hypothesis) and the stamps of its
// timing.tsv (every step).
struct ReplayRows {
  std::vector<formats::FramePoseRow> trajectory;
  std::vector<formats::TimingRecord> timing;
};
ReplayRows ReadReplay(const std::string& dir) {
  ReplayRows out;
  EXPECT_EQ(formats::ParseTrajectoryTsv(formats::ReadTextFile(dir + "/trajectory.tsv").text,
                                        "trajectory.tsv", &out.trajectory),
            "");
  EXPECT_EQ(formats::ParseTimingRows(formats::ReadTextFile(dir + "/timing.tsv").text, "timing.tsv",
                                     &out.timing),
            "");
  return out;
}

std::string FileText(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  std::stringstream text;
  text << in.rdbuf();
  return text.str();
}

// A new directory under /tmp; empty (errno set) when it cannot be made.
std::string MakeTempDir() {
  char dir_template[] = "/tmp/atlas_replay_XXXXXX";  // mkdtemp replaces the X's
  return mkdtemp(dir_template) != nullptr ? std::string(dir_template) : std::string();
}

// A sonar session's options: the B21 ring, the local maps on `sensors`, and a loop queue deep
// enough that a loop that falls behind at times drops nothing.
DaemonOptions SonarSessionOptions(RangeSensors sensors) {
  DaemonOptions o;
  o.sonar.enabled = true;
  o.sonar.ring = SonarRing::kB21_24;
  o.localmap.sensors = sensors;
  o.loop.max_pending_scans = 8;
  return o;
}

class ReplayOfRawSonar : public ::testing::TestWithParam<RangeSensors> {};

// A session recorded with lcm.republish_raw (odometry, laser and sonar raw channels, in the
// order the live loop republished them), replayed by `atlasd --replay` (RunReplay) with the
// same configuration: the same steps, on the same stamps, with the same poses and frames.
TEST_P(ReplayOfRawSonar, ReproducesTheLiveSteps) {
  const std::string dir = MakeTempDir();
  ASSERT_FALSE(dir.empty()) << std::strerror(errno);
  const DaemonOptions o = SonarSessionOptions(GetParam());
  ASSERT_EQ(ValidateDerivedOptions(o), "");
  // The raw channels carry microseconds since the epoch; the replay steps on them.
  const EpochClock epoch = EpochClock::Capture();
  const LiveRun live = RunLive(o, dir + "/session.lcm", 7, epoch);
  const bool both = GetParam() == RangeSensors::kBoth;
  ASSERT_EQ(static_cast<int>(live.rows.size()), live.readings + (both ? live.scans : 0));
  // Live steps in the order added: stamp order, except for the late scans.
  int inversions = 0;
  for (size_t i = 1; i < live.rows.size(); ++i)
    inversions += live.rows[i].stamp < live.rows[i - 1].stamp;
  EXPECT_EQ(inversions, live.late_items);
  if (both) {
    EXPECT_GT(live.late_items, 0);
  }
  ASSERT_TRUE(live.rows.back().pose.valid);
  EXPECT_NEAR(live.rows.back().pose.pose.mean.y, 0.0, 0.15);

  ASSERT_EQ(RunReplay(o, dir + "/session.lcm", dir + "/out"), 0);
  const ReplayRows replay = ReadReplay(dir + "/out");
  ASSERT_EQ(replay.timing.size(), live.rows.size());
  size_t row = 0;  // in trajectory.tsv: the steps with a dominant hypothesis
  for (size_t i = 0; i < live.rows.size(); ++i) {
    const Row& l = live.rows[i];
    SCOPED_TRACE("step " + std::to_string(i));
    // Replayed stamps are the recording's: the live stamps on the epoch clock.
    const auto live_utime = [&](Time t) { return static_cast<double>(epoch.Utime(t)); };
    ASSERT_NEAR(replay.timing[i].stamp_s * 1e6, live_utime(l.stamp), 1.0);
    ASSERT_EQ(replay.timing[i].dominant, l.pose.valid ? l.pose.frame : kNoFrame);
    if (!l.pose.valid) continue;
    ASSERT_LT(row, replay.trajectory.size());
    const formats::FramePoseRow& r = replay.trajectory[row++];
    ASSERT_NEAR(ToSeconds(r.stamp) * 1e6, live_utime(l.stamp), 1.0);
    ASSERT_EQ(r.frame, l.pose.frame);
    ASSERT_NEAR(r.pose.x, l.pose.pose.mean.x, 1e-6);
    ASSERT_NEAR(r.pose.y, l.pose.pose.mean.y, 1e-6);
    ASSERT_NEAR(r.pose.theta, l.pose.pose.mean.theta, 1e-6);
  }
  EXPECT_EQ(row, replay.trajectory.size());
  const std::string summary = FileText(dir + "/out/summary.json");
  EXPECT_NE(summary.find("\"sonar_readings\": " + std::to_string(live.readings) + ","),
            std::string::npos)
      << summary;
  std::filesystem::remove_all(dir);
}

// A recording cut in its last event (lcm-logger killed) replays up to the cut, exit 1, with the
// byte of the cut on stderr; a corrupt one likewise; a file that is neither an LCM log nor a
// CARMEN log is refused before anything is written.
TEST(Replay, SaysWhereABadLogEnds) {
  const std::string dir = MakeTempDir();
  ASSERT_FALSE(dir.empty()) << std::strerror(errno);
  const DaemonOptions o = SonarSessionOptions(RangeSensors::kSonar);
  const EpochClock epoch(0);  // utime on the monotonic clock: the stamps compared as they are
  const LiveRun live = RunLive(o, dir + "/session.lcm", 7, epoch);
  const std::string bytes = FileText(dir + "/session.lcm");
  const size_t cut = bytes.size() - 5;
  std::ofstream(dir + "/cut.lcm", std::ios::binary) << bytes.substr(0, cut);
  ::testing::internal::CaptureStderr();
  EXPECT_EQ(RunReplay(o, dir + "/cut.lcm", dir + "/cut"), 1);
  std::string err = ::testing::internal::GetCapturedStderr();
  EXPECT_NE(err.find(dir + "/cut.lcm: truncated at byte " + std::to_string(cut) +
                     ": the last event, event "),
            std::string::npos)
      << err;
  const ReplayRows replay = ReadReplay(dir + "/cut");
  EXPECT_GE(replay.timing.size() + 1, live.rows.size());  // the last event may have been a reading
  ASSERT_LE(replay.timing.size(), live.rows.size());
  for (size_t i = 0; i < replay.timing.size(); ++i)
    ASSERT_NEAR(replay.timing[i].stamp_s, ToSeconds(live.rows[i].stamp), 1e-6) << i;

  std::string corrupt = bytes;
  const size_t middle = corrupt.find("ATLAS_RAW_SONAR", bytes.size() / 2) - 28;
  corrupt[middle] = 0;  // the sync word of an event in the middle
  std::ofstream(dir + "/corrupt.lcm", std::ios::binary) << corrupt;
  ::testing::internal::CaptureStderr();
  EXPECT_EQ(RunReplay(o, dir + "/corrupt.lcm", dir + "/corrupt"), 1);
  err = ::testing::internal::GetCapturedStderr();
  EXPECT_NE(err.find("corrupt.lcm: corrupt at byte " + std::to_string(middle) + ": event "),
            std::string::npos)
      << err;
  EXPECT_LT(ReadReplay(dir + "/corrupt").timing.size(), live.rows.size());

  std::ofstream(dir + "/text.clf") << "# CARMEN Logfile\n";
  for (const std::string& bad : {dir, dir + "/text.clf", dir + "/missing.lcm"}) {
    ::testing::internal::CaptureStderr();
    EXPECT_EQ(RunReplay(o, bad, dir + "/refused"), 1) << bad;
    err = ::testing::internal::GetCapturedStderr();
    EXPECT_EQ(err.rfind("atlasd: replay: " + bad + ": ", 0), 0u) << err;
    EXPECT_FALSE(std::filesystem::exists(dir + "/refused")) << bad;
  }
  std::filesystem::remove_all(dir);
}

INSTANTIATE_TEST_SUITE_P(Sensors, ReplayOfRawSonar,
                         ::testing::Values(RangeSensors::kSonar, RangeSensors::kBoth),
                         [](const auto& info) {
                           return info.param == RangeSensors::kSonar ? "Sonar" : "Both";
                         });

}  // namespace
}  // namespace atlas
