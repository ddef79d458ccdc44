#pragma once
// The round trip through a separate atlas-fakedev process: shared by the unit test (a slice)
// and the "hil" test (the whole of mit-csail at 10x).

#include <gtest/gtest.h>

#include "tests/hil_drivers/driver_rig.h"
#include "tests/hil_drivers/fakedev_process.h"
#include "tests/hil_drivers/round_trip_check.h"

namespace atlas::hil {

inline void RunFakedevRoundTrip(size_t max_scans, double speed) {
  std::string error;
  auto rec = LoadMitCsail(max_scans, &error);
  if (!rec) GTEST_SKIP() << "mit-csail not available: " << error;
  char tmpl[] = "/tmp/atlas_fakedev_XXXXXX";
  const std::string dir = mkdtemp(tmpl);
  FakedevProcess proc;
  std::vector<std::string> args = {"--log",
                                   MitCsailPath(),
                                   "--speed",
                                   std::to_string(speed),
                                   "--dir",
                                   dir,
                                   "--wait-for-drivers",
                                   "--progress-every",
                                   "5"};
  if (max_scans > 0) {
    args.push_back("--max-scans");
    args.push_back(std::to_string(max_scans));
  }
  ASSERT_TRUE(proc.Launch(dir, args, &error)) << error;
  ASSERT_TRUE(proc.WaitForDevices(20000)) << proc.Output();
  RigOptions o;
  o.speed = speed;
  o.external_dir = dir;
  DriverRig rig(rec, o);
  ASSERT_TRUE(rig.Start(&error)) << error << "\n" << proc.Output();
  const Time limit =
      Now() +
      std::chrono::seconds(static_cast<int64_t>(ToSeconds(rec->end - rec->begin) / speed + 30));
  while (!proc.Exited() && Now() < limit) {
    rig.Drain();
    std::this_thread::sleep_for(std::chrono::milliseconds(1));
  }
  rig.Drain();
  ASSERT_TRUE(proc.Exited()) << "atlas-fakedev did not finish";
  EXPECT_EQ(proc.exit_code(), 0);
  std::printf("%s", proc.Output().c_str());
  const FakedevProcess::Counts sent = proc.DoneCounts();
  ASSERT_TRUE(sent.ok) << proc.Output();

  // Laser: every scan of the log, in order, equal to the unit's precision.
  std::vector<size_t> all(rec->scans.size());
  for (size_t i = 0; i < all.size(); ++i) all[i] = i;
  std::string first;
  const size_t bad = CompareScans(*rec, all, rig.scans, &first);
  size_t beams = 0, no_return_log = 0, no_return_out = 0;
  for (const auto& s : rec->scans)
    for (float r : s.ranges) no_return_log += !IsReturn(r), ++beams;
  for (const auto& s : rig.scans)
    for (float r : s.ranges) no_return_out += !IsReturn(r);
  std::printf(
      "laser: %zu scans in the log, %lu sent, %zu out, %zu differ; beams %zu, no-return "
      "%zu in the log, %zu out\n",
      rec->scans.size(), sent.scans, rig.scans.size(), bad, beams, no_return_log, no_return_out);
  EXPECT_EQ(sent.scans, rec->scans.size());
  EXPECT_EQ(rig.scans.size(), rec->scans.size());
  EXPECT_EQ(bad, 0u) << first;
  EXPECT_EQ(no_return_out, no_return_log);

  // Odometry: one sample per 0x311 sent, each step the log's (as an arc) to 1 mm.
  EXPECT_EQ(rig.odometry.size(), sent.odometry);
  CheckOdometry(ExpectedOdometry(*rec, sent.odometry), rig.odometry, /*expect_all=*/true);

  // Sonar: one reading per SIP sent, each one of the expected, in order.
  EXPECT_EQ(rig.sonar.size(), sent.sips);
  CheckSonar(ExpectedSonar(*rec), rig.sonar, /*expect_all=*/false);

  for (const DriverHealth& h : {rig.laser_->Health(), rig.odo_->Health(), rig.sonar_->Health()}) {
    std::printf(
        "  %-42s msgs %6llu samples %6llu bytes %9llu crc %llu garbage %llu trunc %llu "
        "disc %llu drops %llu\n",
        h.device.c_str(), (unsigned long long)h.messages, (unsigned long long)h.samples,
        (unsigned long long)h.bytes, (unsigned long long)h.bad_crc,
        (unsigned long long)h.garbage_bytes, (unsigned long long)h.truncated,
        (unsigned long long)h.discontinuities, (unsigned long long)h.drops);
    EXPECT_EQ(h.bad_crc, 0u) << h.device;
    EXPECT_EQ(h.discontinuities, 0u) << h.device;
    EXPECT_EQ(h.drops, 0u) << h.device;
  }
  std::error_code ec;
  std::filesystem::remove_all(dir, ec);
  std::filesystem::remove(dir + ".out", ec);
}

}  // namespace atlas::hil
