#include "daemon/atlasd/health_report.h"

#include <gtest/gtest.h>

#include <cstdio>
#include <vector>

#include "core/common/version.h"
#include "core/testing/atlas_test_world.h"
#include "core/testing/fake_step_sink.h"
#include "core/testing/fake_wall_scanner.h"
#include "sim/corridor.h"

namespace atlas {
namespace {

TEST(HealthReport, CountsScanMatchesAndFallbacks) {
  for (const bool enabled : {true, false}) {
    TestWorld maps;
    Atlas atlas(TestWorld::Options(), maps.Factory(), nullptr);
    MapperSettings s;
    s.scan_match.enabled = enabled;
    ASSERT_EQ(ValidateMapperSettings(s), "");
    StepLoop loop(StepLoopOptions{}, s, &atlas);
    FakeStepSink sink;
    FakeWallScanner scanner(sim::CorridorWalls(), FakeLaserOptions{}, 3);
    const int scans = 6;
    for (int i = 0; i < scans; ++i) {
      const Time t = FromSeconds(0.2 * i);
      loop.AddOdometry({t, Pose2{0.1 * i, 0.0, 0.0}});
      LaserScan scan = scanner.Scan(Pose2{3.0 + 0.1 * i, 0.0, 0.0});
      scan.stamp = t;
      loop.AddScan(std::move(scan));
      loop.StepAll(&sink);
    }
    // A scan with no returns: nothing to match against the one before it.
    LaserScan blind = scanner.Scan(Pose2{3.6, 0.0, 0.0});
    for (float& r : blind.ranges) r = kNoReturn;
    blind.stamp = FromSeconds(0.2 * scans);
    loop.AddOdometry({blind.stamp, Pose2{0.1 * scans, 0.0, 0.0}});
    loop.AddScan(std::move(blind));
    loop.StepAll(&sink);
    ASSERT_EQ(loop.steps(), scans + 1);

    HealthInputs in;
    in.start = FromSeconds(0.0);
    in.now = FromSeconds(2.0);
    in.loop = &loop;
    in.step_budget_ms = 10.0;
    const atlasd::health_t h = MakeHealthMessage(in);
    EXPECT_EQ(h.steps, scans + 1);
    EXPECT_EQ(h.version, AtlasVersion());
    if (enabled) {
      EXPECT_EQ(h.scan_matches, scans - 1);
      EXPECT_EQ(h.scan_match_fallbacks, 1);
      EXPECT_NE(h.status.find(" | scan-matched 83%"), std::string::npos) << h.status;
    } else {
      EXPECT_EQ(h.scan_matches, 0);
      EXPECT_EQ(h.scan_match_fallbacks, 0);
      EXPECT_EQ(h.status.find("scan-matched"), std::string::npos) << h.status;
    }
  }
}

// While the laser is away ATLAS_POSE moves with the odometry; the health line's pose is that
// published pose, not the atlas's, which stays at the last scan.
TEST(HealthReport, ThePoseIsThePublishedOneWhileTheLaserIsAway) {
  TestWorld maps;
  Atlas atlas(TestWorld::Options(), maps.Factory(), nullptr);
  StepLoopOptions o;
  o.laser_timeout = std::chrono::milliseconds(500);
  o.dead_reckoning_period = std::chrono::milliseconds(100);
  StepLoop loop(o, MapperSettings{}, &atlas);
  FakeStepSink sink;
  loop.AddOdometry({FromSeconds(0.0), Pose2{}});
  loop.AddScan(ScanAt(0.0));
  loop.StepAll(&sink);
  // 2 s at 1 m/s along x, no scans.
  for (int i = 1; i <= 100; ++i) {
    loop.AddOdometry({FromSeconds(0.02 * i), Pose2{0.02 * i, 0.0, 0.0}});
    loop.StepOne(&sink);
  }
  ASSERT_TRUE(loop.laser_silent());
  ASSERT_EQ(sink.poses.back().source, PoseSource::kOdometryOnly);
  const DominantOutput published = sink.poses.back().pose;
  ASSERT_TRUE(published.valid);
  ASSERT_GT(published.pose.mean.x - atlas.Dominant().pose.mean.x, 1.5);

  HealthInputs in;
  in.start = FromSeconds(0.0);
  in.now = FromSeconds(2.0);
  in.loop = &loop;
  const atlasd::health_t h = MakeHealthMessage(in);
  char want[128];
  std::snprintf(want, sizeof(want), " | pose f%d (%.2f, %.2f, %.2f) q %.2f |", published.frame,
                published.pose.mean.x, published.pose.mean.y, published.pose.mean.theta,
                published.q);
  EXPECT_NE(h.status.find(want), std::string::npos) << h.status << "\nwant" << want;
  EXPECT_NE(h.status.find("LASER FAULT"), std::string::npos) << h.status;
}

}  // namespace
}  // namespace atlas
