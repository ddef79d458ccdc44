#include "core/mapper/step_loop.h"

#include <gtest/gtest.h>

#include <cmath>
#include <random>
#include <vector>

#include "core/testing/atlas_test_world.h"
#include "core/testing/fake_sonar_ring.h"
#include "core/testing/fake_step_sink.h"
#include "core/testing/fake_wall_scanner.h"
#include "sim/corridor.h"

namespace atlas {
namespace {

class StepLoopTest : public ::testing::Test {
 protected:
  StepLoopTest() : atlas_(TestWorld::Options(), world_.Factory(), nullptr) {}
  // The laser counts as away after 0.5 s without a scan; dead reckoning every 100 ms.
  static StepLoopOptions DeadReckoningOptions() {
    StepLoopOptions o;
    o.laser_timeout = std::chrono::milliseconds(500);
    o.dead_reckoning_period = std::chrono::milliseconds(100);
    return o;
  }
  static void StepOneScanAtZero(StepLoop* loop, FakeStepSink* sink) {
    loop->AddOdometry({FromSeconds(0.0), Pose2{}});
    loop->AddScan(ScanAt(0.0));
    loop->StepAll(sink);
  }
  // The fake maps move the robot by exactly the odometry increment they are given; scan
  // matching (on by default) would replace it, and has its own tests (StepLoopScanMatch).
  static MapperSettings WithoutScanMatching() {
    MapperSettings s;
    s.scan_match.enabled = false;
    return s;
  }
  TestWorld world_;
  Atlas atlas_;
  MapperSettings settings_ = WithoutScanMatching();
};

TEST_F(StepLoopTest, OdometryIsInterpolatedToTheScanStamp) {
  StepLoopOptions o;
  StepLoop loop(o, settings_, &atlas_);
  FakeStepSink sink;
  loop.AddOdometry({FromSeconds(10.0), Pose2{0, 0, 0}});
  loop.AddOdometry({FromSeconds(10.1), Pose2{1.0, 0, 0}});
  loop.AddScan(ScanAt(10.0));
  loop.AddScan(ScanAt(10.05));
  EXPECT_EQ(loop.StepAll(&sink), 2);
  ASSERT_EQ(sink.poses.size(), 2u);
  ASSERT_TRUE(sink.poses[1].pose.valid);
  EXPECT_EQ(sink.poses[1].source, PoseSource::kScan);
  EXPECT_EQ(sink.poses[1].stamp, FromSeconds(10.05));
  // The fake maps move the robot by exactly the odometry increment: 0.5 m of the 1 m.
  EXPECT_NEAR(sink.poses[1].pose.pose.mean.x - sink.poses[0].pose.pose.mean.x, 0.5, 1e-6);
  EXPECT_EQ(loop.steps(), 2);
  EXPECT_EQ(sink.last_steps, 2);
}

// laser_time_offset: the odometry is looked up at stamp + offset, the pose keeps the stamp.
// The robot stands until 10.1 s and then drives 1 m in 0.1 s: scans stamped 10.1 and 10.2 but
// taken 0.1 s earlier saw the robot standing, so the fake maps (which follow the odometry
// increment exactly) must not move it; without the offset they move it by the whole metre.
TEST_F(StepLoopTest, LaserTimeOffsetShiftsTheOdometryLookupNotTheStamp) {
  for (const double offset : {0.0, -0.1}) {
    Atlas atlas(TestWorld::Options(), world_.Factory(), nullptr);
    StepLoopOptions o;
    o.laser_time_offset = FromSeconds(offset).time_since_epoch();
    ASSERT_EQ(o.Validate(), "");
    StepLoop loop(o, settings_, &atlas);
    FakeStepSink sink;
    loop.AddOdometry({FromSeconds(10.0), Pose2{0, 0, 0}});
    loop.AddOdometry({FromSeconds(10.1), Pose2{0, 0, 0}});
    loop.AddOdometry({FromSeconds(10.2), Pose2{1.0, 0, 0.2}});
    loop.AddScan(ScanAt(10.1));
    loop.AddScan(ScanAt(10.2));
    EXPECT_EQ(loop.StepAll(&sink), 2);
    ASSERT_EQ(sink.poses.size(), 2u);
    EXPECT_EQ(sink.poses[0].stamp, FromSeconds(10.1));
    EXPECT_EQ(sink.poses[1].stamp, FromSeconds(10.2));
    EXPECT_EQ(loop.last_scan_stamp(), FromSeconds(10.2));
    const Pose2 moved = Between(sink.poses[0].pose.pose.mean, sink.poses[1].pose.pose.mean);
    EXPECT_NEAR(moved.x, offset == 0.0 ? 1.0 : 0.0, 1e-6) << offset;
    EXPECT_NEAR(moved.theta, offset == 0.0 ? 0.2 : 0.0, 1e-6) << offset;
  }
}

// stamp_resolution: everything added is truncated to whole microseconds before the loop uses
// it (the pose's stamp, the odometry lookup, last_scan_stamp); the default keeps nanoseconds.
TEST_F(StepLoopTest, StampsAreTruncatedToTheStampResolution) {
  for (const Duration resolution : {Duration::zero(), Duration(std::chrono::microseconds(1))}) {
    Atlas atlas(TestWorld::Options(), world_.Factory(), nullptr);
    StepLoopOptions o;
    o.stamp_resolution = resolution;
    ASSERT_EQ(o.Validate(), "");
    StepLoop loop(o, settings_, &atlas);
    FakeStepSink sink;
    // Odometry 1 m apart 1 ms apart; the scan 0.999 us after the first sample.
    loop.AddOdometry({Time(std::chrono::nanoseconds(1'000'000'000)), Pose2{}});
    loop.AddScan(ScanAt(1.0));
    loop.AddOdometry({Time(std::chrono::nanoseconds(1'001'000'000)), Pose2{1.0, 0, 0}});
    LaserScan scan = ScanAt(1.0);
    scan.stamp = Time(std::chrono::nanoseconds(1'000'000'999));
    loop.AddScan(std::move(scan));
    ASSERT_EQ(loop.StepAll(&sink), 2);
    ASSERT_EQ(sink.poses.size(), 2u);
    const Pose2 moved = Between(sink.poses[0].pose.pose.mean, sink.poses[1].pose.pose.mean);
    if (resolution == Duration::zero()) {
      EXPECT_EQ(sink.poses[1].stamp.time_since_epoch().count(), 1'000'000'999);
      EXPECT_NEAR(moved.x, 0.000999, 1e-9);  // 999 ns of the 1 ms between the samples
    } else {
      EXPECT_EQ(sink.poses[1].stamp.time_since_epoch().count(), 1'000'000'000);
      EXPECT_NEAR(moved.x, 0.0, 1e-9);
    }
    EXPECT_EQ(loop.last_scan_stamp(), sink.poses[1].stamp);
  }
}

TEST_F(StepLoopTest, StampResolutionIsValidated) {
  StepLoopOptions o;
  o.stamp_resolution = Duration(-1);
  EXPECT_NE(o.Validate().find("stamp_resolution"), std::string::npos);
  o.stamp_resolution = std::chrono::milliseconds(1001);
  EXPECT_NE(o.Validate().find("stamp_resolution"), std::string::npos);
}

TEST_F(StepLoopTest, LaserTimeOffsetBeyondOneSecondIsRejected) {
  StepLoopOptions o;
  o.laser_time_offset = std::chrono::milliseconds(-1001);
  EXPECT_NE(o.Validate().find("laser_time_offset"), std::string::npos);
  o.laser_time_offset = std::chrono::milliseconds(1001);
  EXPECT_NE(o.Validate(), "");
  o.laser_time_offset = std::chrono::milliseconds(-1000);
  EXPECT_EQ(o.Validate(), "");
}

TEST_F(StepLoopTest, DropsTheOldestScansWhenBehind) {
  StepLoopOptions o;
  o.max_pending_scans = 2;
  StepLoop loop(o, settings_, &atlas_);
  FakeStepSink sink;
  loop.AddOdometry({FromSeconds(0.0), Pose2{}});
  for (int i = 0; i < 5; ++i) loop.AddScan(ScanAt(0.01 * i));
  EXPECT_EQ(loop.dropped_scans(), 3);
  EXPECT_EQ(loop.Pending(), 2u);
  EXPECT_EQ(loop.StepAll(&sink), 2);
  ASSERT_EQ(sink.poses.size(), 2u);
  EXPECT_EQ(sink.poses[0].stamp, FromSeconds(0.03));  // the newest two survived, in order
  EXPECT_EQ(sink.poses[1].stamp, FromSeconds(0.04));
}

TEST_F(StepLoopTest, CountsOverrunsAgainstTheBudget) {
  StepLoopOptions o;
  o.step_budget = Duration(1);  // 1 ns: every step overruns
  StepLoop loop(o, settings_, &atlas_);
  FakeStepSink sink;
  loop.AddOdometry({FromSeconds(0.0), Pose2{}});
  loop.AddScan(ScanAt(0.0));
  loop.StepAll(&sink);
  EXPECT_EQ(loop.overruns(), 1);
  const StepTimeSummary s = loop.TakePeriod();
  EXPECT_EQ(s.steps, 1);
  EXPECT_GT(s.max_us, 0.0f);
  EXPECT_LE(s.min_us, s.median_us);
  EXPECT_LE(s.median_us, s.p99_us);
  EXPECT_LE(s.p99_us, s.max_us);
  EXPECT_EQ(loop.TakePeriod().steps, 0);  // a period is taken once
}

TEST_F(StepLoopTest, DeadReckonsWhileTheLaserIsAwayAndRecovers) {
  StepLoop loop(DeadReckoningOptions(), settings_, &atlas_);
  FakeStepSink sink;
  StepOneScanAtZero(&loop, &sink);
  const DominantOutput at_scan = sink.poses.back().pose;
  sink.poses.clear();
  // 2 s of odometry at 50 Hz driving along x at 1 m/s, no scans.
  for (int i = 1; i <= 100; ++i) {
    loop.AddOdometry({FromSeconds(0.02 * i), Pose2{0.02 * i, 0, 0}});
    EXPECT_FALSE(loop.StepOne(&sink));
  }
  EXPECT_TRUE(loop.laser_silent());
  ASSERT_GE(sink.poses.size(), 10u);  // ~1.5 s of silence at 10 Hz
  EXPECT_LE(sink.poses.size(), 16u);
  const RecordedPose& last = sink.poses.back();
  EXPECT_EQ(last.source, PoseSource::kOdometryOnly);
  EXPECT_EQ(last.pose.frame, at_scan.frame);
  // Moved by the odometry since the scan, up to the newest sample it was published at.
  EXPECT_NEAR(last.pose.pose.mean.x - at_scan.pose.mean.x, ToSeconds(last.stamp), 1e-6);
  EXPECT_GT(ToSeconds(last.stamp), 1.85);
  EXPECT_GT(last.pose.pose.cov.trace(), at_scan.pose.cov.trace());  // uncertainty grew
  // The laser is back.
  loop.AddScan(ScanAt(2.0));
  EXPECT_TRUE(loop.StepOne(&sink));
  EXPECT_FALSE(loop.laser_silent());
  EXPECT_EQ(sink.poses.back().source, PoseSource::kScan);
}

// While the laser is away the robot turns one way and back: the published uncertainty grows
// with the path turned, never shrinks because the net rotation since the scan does.
TEST_F(StepLoopTest, DeadReckonedUncertaintyGrowsWithThePathNotTheNetMotion) {
  StepLoop loop(DeadReckoningOptions(), settings_, &atlas_);
  FakeStepSink sink;
  StepOneScanAtZero(&loop, &sink);
  sink.poses.clear();
  // 4 s turning on the spot at +1 rad/s, then 4 s at -1 rad/s, back to the heading of the scan.
  for (int i = 1; i <= 400; ++i) {
    const double t = 0.02 * i;
    const double theta = t <= 4.0 ? t : 8.0 - t;
    loop.AddOdometry({FromSeconds(t), Pose2{0, 0, WrapAngle(theta)}});
    loop.StepOne(&sink);
  }
  ASSERT_GE(sink.poses.size(), 60u);
  for (size_t k = 1; k < sink.poses.size(); ++k) {
    ASSERT_EQ(sink.poses[k].source, PoseSource::kOdometryOnly);
    EXPECT_GE(sink.poses[k].pose.pose.cov(2, 2), sink.poses[k - 1].pose.pose.cov(2, 2))
        << "at " << ToSeconds(sink.poses[k].stamp) << " s";
  }
  // Nearly back at the scan's heading, after almost 8 rad of turning: the variance is that of
  // the path.
  const RecordedPose& last = sink.poses.back();
  EXPECT_NEAR(last.pose.pose.mean.theta, 8.0 - ToSeconds(last.stamp), 1e-6);
  EXPECT_LT(last.pose.pose.mean.theta, 0.15);
  const size_t half = sink.poses.size() / 2;
  EXPECT_GT(sink.poses.back().pose.pose.cov(2, 2), 1.5 * sink.poses[half].pose.pose.cov(2, 2));
}

TEST_F(StepLoopTest, PublishesOnOdometryAloneWhenNoScanEverCame) {
  StepLoopOptions o;
  StepLoop loop(o, settings_, &atlas_);
  FakeStepSink sink;
  for (int i = 0; i <= 50; ++i) {
    loop.AddOdometry({FromSeconds(5.0 + 0.02 * i), Pose2{0.01 * i, 0, 0}});
    loop.StepOne(&sink);
  }
  EXPECT_TRUE(loop.laser_silent());
  ASSERT_FALSE(sink.poses.empty());
  EXPECT_FALSE(sink.poses.back().pose.valid);  // no frame yet
  EXPECT_NEAR(sink.poses.back().pose.pose.mean.x, 0.5, 1e-6);
}

// localmap.sensors "both": scans and sonar readings are stepped in the order added, each once;
// InStampOrder gives a drain's items in stamp order. An item added after a newer one (a
// reader preempted between its arrival stamp and its push) is stepped after it, with the
// odometry increment going backwards: live and replay (which adds in log order) agree.
TEST_F(StepLoopTest, StepsScansAndSonarReadingsInTheOrderAdded) {
  StepLoopOptions o;
  o.max_pending_scans = 4;
  StepLoop loop(o, settings_, &atlas_);
  FakeStepSink sink;
  loop.AddOdometry({FromSeconds(0.0), Pose2{}});
  loop.AddOdometry({FromSeconds(0.4), Pose2{0.4, 0, 0}});
  std::vector<SonarReading> readings;
  readings.push_back(SonarAt(0.05));
  readings.push_back(SonarAt(0.15));
  std::vector<LaserScan> scans;
  scans.push_back(ScanAt(0.0));
  scans.push_back(ScanAt(0.1));
  scans.push_back(ScanAt(0.2));
  InStampOrder(
      readings, scans, [&](SonarReading& r) { loop.AddSonar(std::move(r)); },
      [&](LaserScan& s) { loop.AddScan(std::move(s)); });
  EXPECT_EQ(loop.Pending(), 5u);
  EXPECT_EQ(loop.StepAll(&sink), 5);
  loop.AddSonar(SonarAt(0.3));
  loop.AddScan(ScanAt(0.25));  // late
  EXPECT_EQ(loop.StepAll(&sink), 2);
  ASSERT_EQ(sink.poses.size(), 7u);
  const double order[] = {0.0, 0.05, 0.1, 0.15, 0.2, 0.3, 0.25};
  for (int i = 0; i < 7; ++i) {
    EXPECT_EQ(sink.poses[i].stamp, FromSeconds(order[i]));
    EXPECT_EQ(sink.poses[i].source, PoseSource::kScan);
  }
  // The fake maps follow the odometry, interpolated to each item's stamp (backwards last).
  EXPECT_NEAR(sink.poses[3].pose.pose.mean.x - sink.poses[0].pose.pose.mean.x, 0.15, 1e-6);
  EXPECT_NEAR(sink.poses[6].pose.pose.mean.x - sink.poses[5].pose.pose.mean.x, -0.05, 1e-6);
  EXPECT_EQ(atlas_.StepCount(), 7);
  // The sonar ring has its own bound: the oldest readings are dropped and counted.
  for (int i = 0; i < 6; ++i) loop.AddSonar(SonarAt(0.4 + 0.01 * i));
  EXPECT_EQ(loop.dropped_sonar(), 2);
  EXPECT_EQ(loop.dropped_scans(), 0);
}

// scan_match.enabled: each scan after the first is matched against the one before it and the
// maps predict with the matched increment. The fake maps of TestWorld move the robot by exactly
// the increment they are given, so the dominant pose shows which increment was used. The
// wheels here turn 1.5 degrees a step more than the robot (27 degrees over the run): with
// matching the heading drifts by a fraction of a degree, without it by the whole 27 degrees.
// A sonar step drops the reference: the next scan is not matched.
TEST(StepLoopScanMatch, MatchedIncrementsReplaceAWrongOdometryHeading) {
  FakeLaserOptions laser;
  laser.sensor_pose = Pose2{0.1, 0.0, 0.0};
  const std::vector<sim::Wall> world = sim::CorridorWalls();
  for (const bool enabled : {true, false}) {
    TestWorld maps;
    Atlas atlas(TestWorld::Options(), maps.Factory(), nullptr);
    MapperSettings s;
    s.scan_match.enabled = enabled;
    // The heading part of the B21 profile (config/atlasd.toml): 1.5 degrees a step is within
    // its sigma, as the odometry's prior must allow for the matched increment to prevail.
    s.local_map.odometry.theta_var_per_m = 0.005;
    s.local_map.odometry.theta_var_per_rad = 0.03;
    ASSERT_EQ(ValidateMapperSettings(s), "");
    StepLoop loop(StepLoopOptions{}, s, &atlas);
    FakeStepSink sink;
    FakeWallScanner scanner(world, laser, 9);
    const Pose2 start{3.0, 0.0, 0.0};
    const int scans = 19;
    Pose2 odometry;
    for (int i = 0; i < scans; ++i) {
      const double t = 0.2 * i;
      const Pose2 robot = Compose(start, Pose2{0.1 * i, 0.0, 0.0});
      if (i > 0) odometry = Compose(odometry, Pose2{0.1, 0.0, 0.026});
      loop.AddOdometry({FromSeconds(t), odometry});
      LaserScan scan = scanner.Scan(robot);
      scan.stamp = FromSeconds(t);
      loop.AddScan(std::move(scan));
      loop.StepAll(&sink);
    }
    EXPECT_EQ(loop.steps(), scans);
    EXPECT_EQ(loop.scan_matches(), enabled ? scans - 1 : 0);
    EXPECT_EQ(loop.scan_match_fallbacks(), 0);
    // The robot drives straight: every heading change between two consecutive poses in one
    // frame is an error.
    double drift = 0.0;
    for (size_t i = 1; i < sink.poses.size(); ++i) {
      const DominantOutput &p = sink.poses[i - 1].pose, &q = sink.poses[i].pose;
      ASSERT_TRUE(q.valid);
      if (p.frame == q.frame) drift += WrapAngle(q.pose.mean.theta - p.pose.mean.theta);
    }
    if (enabled) {
      EXPECT_LT(std::abs(drift), 0.5 * 3.14159265358979 / 180.0);
    } else {
      EXPECT_NEAR(drift, 0.026 * (scans - 1), 1e-6);
    }
  }

  MapperSettings s;
  s.scan_match.enabled = true;
  s.sensors = RangeSensors::kBoth;
  s.sonar_ring = FakeSonarRing24();
  std::unique_ptr<Atlas> atlas = MakeAtlas(s);
  StepLoop loop(StepLoopOptions{}, s, atlas.get());
  FakeStepSink sink;
  FakeWallScanner scanner(world, laser, 9);
  loop.AddOdometry({FromSeconds(0.0), Pose2{3.0, 0.0, 0.0}});
  loop.AddOdometry({FromSeconds(1.0), Pose2{3.0, 0.0, 0.0}});
  LaserScan a = scanner.Scan(Pose2{3.0, 0.0, 0.0}), b = scanner.Scan(Pose2{3.0, 0.0, 0.0});
  a.stamp = FromSeconds(0.1);
  b.stamp = FromSeconds(0.3);
  SonarReading r;
  r.stamp = FromSeconds(0.2);
  loop.AddScan(std::move(a));
  loop.AddSonar(std::move(r));
  loop.AddScan(std::move(b));
  EXPECT_EQ(loop.StepAll(&sink), 3);
  EXPECT_EQ(loop.scan_matches(), 0);
}

// localmap.sensors "sonar": MakeAtlas builds sonar-only maps, and a robot driving down a
// corridor with a 24-transducer ring (the tangent model, core/testing/fake_sonar_ring.h) maps its
// walls and is localised by sonar steps alone; no laser, and no dead reckoning.
TEST(StepLoopSonar, SonarOnlyAtlasMapsACorridor) {
  MapperSettings s;
  s.sensors = RangeSensors::kSonar;
  s.sonar_ring = FakeSonarRing24();
  ASSERT_EQ(ValidateMapperSettings(s), "");
  MapperSettings no_ring = s;
  no_ring.sonar_ring.clear();
  EXPECT_NE(ValidateMapperSettings(no_ring), "");
  std::unique_ptr<Atlas> atlas = MakeAtlas(s);
  StepLoop loop(StepLoopOptions{}, s, atlas.get());
  FakeStepSink sink;
  const std::vector<sim::Wall> walls = {{Vec2(-5, 1.2), Vec2(30, 1.2)},
                                        {Vec2(-5, -1.2), Vec2(30, -1.2)}};
  std::mt19937_64 rng(5);
  // 12 s at 0.5 m/s along the corridor; odometry at 50 Hz, the ring at 10 Hz.
  int readings = 0;
  for (int i = 0; i <= 600; ++i) {
    const double t = 0.02 * i;
    const Pose2 robot{0.5 * t, 0.0, 0.0};
    loop.AddOdometry({FromSeconds(t), robot});
    if (i % 5 == 0) {
      SonarReading r = FireFakeSonarRing(walls, s.sonar_ring, robot, 0.01, rng);
      r.stamp = FromSeconds(t);
      loop.AddSonar(std::move(r));
      ++readings;
    }
    loop.StepAll(&sink);
  }
  EXPECT_EQ(loop.steps(), readings);
  EXPECT_FALSE(loop.laser_silent());
  ASSERT_FALSE(sink.poses.empty());
  for (const RecordedPose& r : sink.poses) EXPECT_EQ(r.source, PoseSource::kScan);
  const DominantOutput d = atlas->Dominant();
  ASSERT_TRUE(d.valid);
  const LocalMap& map = *atlas->Graph().Frame(d.frame).map;
  // Both walls mapped: lines at y = +-1.2 in the start frame (frame 0: the robot did not leave
  // it in 6 m).
  EXPECT_EQ(d.frame, 0);
  int walls_found = 0;
  for (const MapLine& l : map.Lines()) {
    walls_found +=
        std::abs(std::abs(l.rho) - 1.2) < 0.1 && std::abs(std::abs(std::sin(l.alpha)) - 1.0) < 0.01;
  }
  EXPECT_GE(walls_found, 2);
  EXPECT_NEAR(d.pose.mean.y, 0.0, 0.1);
  EXPECT_NEAR(d.pose.mean.theta, 0.0, 0.03);
  EXPECT_NEAR(d.pose.mean.x, 6.0, 0.3);
}

// Sonar alone maps with the sonar's Condition 2 settings (map_match.h, SonarMapMatchOptions),
// the laser and both with the laser's (LaserMapMatchOptions): default redundancy, lines of
// unknown correlation, a 1 m prior half-width, a 0.02 rad angle floor. Sonar maps' lines are of
// unknown correlation too (off in MapMatchOptions{}).
TEST(StepLoopSonar, SonarAtlasMatchesMapsWithTheSonarSettings) {
  MapperSettings s;
  const MapMatchOptions laser = LaserMapMatchOptions();
  for (RangeSensors sensors : {RangeSensors::kLaser, RangeSensors::kBoth}) {
    s.sensors = sensors;
    if (sensors == RangeSensors::kBoth) s.sonar_ring = FakeSonarRing24();
    const MapMatchOptions m = MakeAtlas(s)->Options().match;
    EXPECT_EQ(m.redundancy_sigma, MapMatchOptions{}.redundancy_sigma);
    EXPECT_TRUE(m.unknown_line_correlation);
    EXPECT_EQ(m.alternative_sigmas, laser.alternative_sigmas);
    EXPECT_EQ(m.redundancy_prior_halfwidth, laser.redundancy_prior_halfwidth);
    EXPECT_EQ(m.sigma_alpha_floor, laser.sigma_alpha_floor);
  }
  EXPECT_LT(laser.redundancy_prior_halfwidth, MapMatchOptions{}.redundancy_prior_halfwidth);
  EXPECT_GT(laser.sigma_alpha_floor, MapMatchOptions{}.sigma_alpha_floor);
  s.sensors = RangeSensors::kSonar;
  const MapMatchOptions m = MakeAtlas(s)->Options().match;
  EXPECT_EQ(m.redundancy_sigma, SonarMapMatchOptions().redundancy_sigma);
  EXPECT_EQ(m.redundancy_prior_halfwidth, SonarMapMatchOptions().redundancy_prior_halfwidth);
  EXPECT_LT(m.redundancy_sigma, MapMatchOptions{}.redundancy_sigma);
  EXPECT_TRUE(m.unknown_line_correlation);
  EXPECT_FALSE(MapMatchOptions{}.unknown_line_correlation);
}

// A saved atlas of laser maps is not read as one of sonar maps (start moves it aside).
TEST(StepLoopSonar, AtlasImageOfTheOtherMapKindIsRefused) {
  MapperSettings laser;
  std::unique_ptr<Atlas> a = MakeAtlas(laser);
  a->Step(Pose2{}, TestScan());
  MapperSettings sonar;
  sonar.sensors = RangeSensors::kSonar;
  sonar.sonar_ring = FakeSonarRing24();
  EXPECT_FALSE(MakeAtlas(sonar)->Deserialize(a->Serialize()));
  EXPECT_TRUE(MakeAtlas(laser)->Deserialize(a->Serialize()));
  std::unique_ptr<Atlas> b = MakeAtlas(sonar);
  b->Step(Pose2{}, SonarAt(0.0));
  EXPECT_FALSE(MakeAtlas(laser)->Deserialize(b->Serialize()));
  EXPECT_TRUE(MakeAtlas(sonar)->Deserialize(b->Serialize()));
}

}  // namespace
}  // namespace atlas
