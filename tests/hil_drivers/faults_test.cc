// A test per fault kind: the fakes inject it into every device that can have it, the drivers
// count each fault, recover and go on delivering, and what they deliver is still equal to
// what was sent intact.
#include <gtest/gtest.h>

#include "tests/hil_drivers/driver_rig.h"
#include "tests/hil_drivers/round_trip_check.h"

namespace atlas::hil {
namespace {

std::shared_ptr<const fake::Recording> Slice(size_t scans) {
  std::string error;
  auto rec = LoadMitCsail(scans, &error);
  if (!rec) std::printf("mit-csail not available: %s\n", error.c_str());
  return rec;
}

// Runs the rig to the end; the drivers must be running at the end and what they delivered
// must be what was sent intact, in order. SIPs the fake controller sends while the sonar driver is
// still handshaking again are lost on the way (sonar_exact = false).
void RunAndCheck(DriverRig& rig, bool sonar_exact = true) {
  std::string error;
  ASSERT_TRUE(rig.Start(&error)) << error;
  rig.RunToEnd(std::chrono::seconds(25));
  const MissingRuns missing = CheckRoundTrip(rig, /*expect_all=*/false);
  // Messages in flight when a device is unplugged, and those the device sends while its line is
  // reopened and the driver's start-up runs, may be lost: at most two unbroken runs per
  // disconnection, as long as the reopen takes (on a loaded machine 0.2 s of laser scans and
  // SIPs). A message lost anywhere else is a second run. Otherwise everything sent intact
  // comes out. Odometry frames are not matched by content: a few per disconnection.
  EXPECT_LE(missing.laser, 2 * rig.laser_->Health().disconnects);
  EXPECT_LE(rig.base_->sent_intact().total() - rig.odometry.size(),
            3 * rig.odo_->Health().disconnects);
  if (sonar_exact) {
    EXPECT_LE(missing.sonar, 2 * rig.sonar_->Health().disconnects);
  }
  ASSERT_EQ(rig.states_at_end.size(), 3u) << "the fakes did not finish playing";
  for (DriverState s : rig.states_at_end) EXPECT_EQ(s, DriverState::kRunning) << ToString(s);
}

TEST(FaultsTest, GarbageIsCountedAndSkipped) {
  auto rec = Slice(150);
  if (!rec) GTEST_SKIP();
  RigOptions o;
  o.speed = 20;
  o.laser_faults.garbage_every = 7;
  o.sonar_faults.garbage_every = 7;
  o.odometry_faults.garbage_every = 50;
  DriverRig rig(rec, o);
  RunAndCheck(rig);
  const auto& fl = rig.lms_->fault_counts();
  const auto& fs = rig.p2os_->fault_counts();
  const auto& fb = rig.base_->fault_counts();
  EXPECT_GT(fl.garbage.load(), 10u);
  EXPECT_EQ(rig.laser_->Health().garbage_bytes, fl.garbage.load() * o.laser_faults.garbage_bytes);
  EXPECT_EQ(rig.sonar_->Health().garbage_bytes, fs.garbage.load() * o.sonar_faults.garbage_bytes);
  EXPECT_EQ(rig.odo_->Health().bad_messages, fb.garbage.load());
  // Garbage does not cost a single message.
  EXPECT_EQ(rig.scans.size(), rec->scans.size());
}

TEST(FaultsTest, CorruptCrcIsCountedAndDropped) {
  auto rec = Slice(150);
  if (!rec) GTEST_SKIP();
  RigOptions o;
  o.speed = 20;
  o.laser_faults.corrupt_crc_every = 9;
  o.sonar_faults.corrupt_crc_every = 9;
  DriverRig rig(rec, o);
  RunAndCheck(rig);
  const uint64_t nl = rig.lms_->fault_counts().corrupted.load();
  const uint64_t ns = rig.p2os_->fault_counts().corrupted.load();
  EXPECT_GT(nl, 10u);
  EXPECT_GE(rig.laser_->Health().bad_crc, nl);
  EXPECT_GE(rig.sonar_->Health().bad_crc, ns);
  EXPECT_EQ(rig.scans.size(), rec->scans.size() - nl);
}

TEST(FaultsTest, TruncatedMessagesAreCountedAndDropped) {
  auto rec = Slice(150);
  if (!rec) GTEST_SKIP();
  RigOptions o;
  o.speed = 20;
  o.laser_faults.truncate_every = 8;
  o.sonar_faults.truncate_every = 8;
  o.odometry_faults.truncate_every = 40;
  DriverRig rig(rec, o);
  RunAndCheck(rig);
  const uint64_t nl = rig.lms_->fault_counts().truncated.load();
  const uint64_t ns = rig.p2os_->fault_counts().truncated.load();
  const uint64_t nb = rig.base_->fault_counts().truncated.load();
  EXPECT_GT(nl, 10u);
  const DriverHealth hl = rig.laser_->Health();
  const DriverHealth hs = rig.sonar_->Health();
  // A cut telegram followed by silence is "truncated"; followed at once by the next one it
  // fails its CRC instead. Either way it is counted, and only it is lost.
  EXPECT_GE(hl.truncated + hl.bad_crc, nl);
  EXPECT_GE(hs.truncated + hs.bad_crc, ns);
  EXPECT_EQ(rig.odo_->Health().bad_messages, nb);
  EXPECT_EQ(rig.scans.size(), rec->scans.size() - nl);
}

TEST(FaultsTest, OdometryJumpIsADiscontinuityNotAPoseJump) {
  auto rec = Slice(150);
  if (!rec) GTEST_SKIP();
  RigOptions o;
  o.speed = 20;
  o.odometry_faults.jump_every = 150;
  DriverRig rig(rec, o);
  RunAndCheck(rig);
  const uint64_t jumps = rig.base_->fault_counts().jumps.load();
  EXPECT_GE(jumps, 5u);
  EXPECT_EQ(rig.odo_->Health().discontinuities, jumps);
  // No sample moves further than the robot could in its step.
  double worst = 0;
  for (size_t k = 1; k < rig.odometry.size(); ++k) {
    const Pose2 d = Between(rig.odometry[k - 1].pose, rig.odometry[k].pose);
    worst = std::max(worst, std::hypot(d.x, d.y));
  }
  EXPECT_LT(worst, 0.1);
}

TEST(FaultsTest, DeviceUnpluggedAndBackIsReopened) {
  auto rec = Slice(300);
  if (!rec) GTEST_SKIP();
  RigOptions o;
  o.speed = 20;
  for (auto* f : {&o.laser_faults, &o.sonar_faults, &o.odometry_faults}) {
    f->drop_after_s = 0.8;
    f->drop_for_s = 0.6;
  }
  DriverRig rig(rec, o);
  RunAndCheck(rig);
  for (const DriverHealth& h : {rig.laser_->Health(), rig.odo_->Health(), rig.sonar_->Health()}) {
    EXPECT_EQ(h.disconnects, 1u) << h.device;
    EXPECT_EQ(h.reconnects, 1u) << h.device;
    EXPECT_GE(h.connect_failures, 1u) << h.device;  // the path was gone meanwhile
    EXPECT_FALSE(h.last_error.empty()) << h.device;
  }
  // Data flowed again after the drop: the last scan out is one of the last sent, and most of
  // what was sent intact came out (of all sent, not of the slice: on a loaded machine the fake
  // itself sends fewer).
  ASSERT_FALSE(rig.scans.empty());
  EXPECT_GT(rig.lms_->sent_intact().Items().back(), rec->scans.size() - 5);
  EXPECT_GT(rig.scans.size(), rig.lms_->sent_intact().total() / 2);
}

TEST(FaultsTest, ShortStallIsReportedAndOutlived) {
  auto rec = Slice(300);
  if (!rec) GTEST_SKIP();
  RigOptions o;
  o.speed = 20;
  for (auto* f : {&o.laser_faults, &o.sonar_faults, &o.odometry_faults}) {
    f->stall_after_s = 0.6;
    f->stall_for_s = 0.8;  // longer than the stall timeout (0.4 s), shorter than a reopen
  }
  DriverRig rig(rec, o);
  RunAndCheck(rig);
  for (const DriverHealth& h : {rig.laser_->Health(), rig.odo_->Health(), rig.sonar_->Health()}) {
    EXPECT_GE(h.stalls, 1u) << h.device;
    EXPECT_EQ(h.disconnects, 0u) << h.device;
  }
  EXPECT_GT(rig.lms_->sent_intact().Items().back(), rec->scans.size() - 5);
}

TEST(FaultsTest, LongStallRestartsTheDeviceWhichIsFoundAtItsNewRate) {
  auto rec = Slice(600);
  if (!rec) GTEST_SKIP();
  RigOptions o;
  o.speed = 20;
  for (auto* f : {&o.laser_faults, &o.sonar_faults, &o.odometry_faults}) {
    f->stall_after_s = 0.5;
    f->stall_for_s = 2.2;  // past reopen_after_silence (1.5 s) and the P2OS watchdog (2 s)
  }
  DriverRig rig(rec, o);
  RunAndCheck(rig, /*sonar_exact=*/false);
  for (const DriverHealth& h : {rig.laser_->Health(), rig.odo_->Health(), rig.sonar_->Health()}) {
    EXPECT_GE(h.stalls, 1u) << h.device;
    EXPECT_GE(h.disconnects, 1u) << h.device;
    EXPECT_GE(h.reconnects, 1u) << h.device;
  }
  // The scanner stayed at 500000 baud: the restarted driver found it there, not at 9600.
  EXPECT_EQ(rig.laser_->found_baud(), 500000);
  EXPECT_GE(rig.lms_->commands_ignored_wrong_rate(), 1u);
  EXPECT_GT(rig.lms_->sent_intact().Items().back(), rec->scans.size() - 5);
}

}  // namespace
}  // namespace atlas::hil
