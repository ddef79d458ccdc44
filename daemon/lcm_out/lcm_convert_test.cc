#include "daemon/lcm_out/lcm_convert.h"

#include <gtest/gtest.h>

#include <cmath>
#include <lcm/lcm-cpp.hpp>

#include "core/testing/atlas_test_world.h"
#include "daemon/lcm_out/atlas_publisher.h"

namespace atlas {
namespace {

TEST(LcmConvertTest, RawLaserRoundTripsExactly) {
  LaserScan s;
  s.stamp = FromSeconds(12.345678);
  s.angle_min = -1.5f;
  s.angle_increment = 0.01f;
  s.max_range = 8.0f;
  s.ranges = {1.0f, kNoReturn, 2.5f};
  s.sensor_pose = Pose2{0.1, -0.2, 0.3};
  const LaserScan back = FromLaserMessage(ToLaserMessage(s));
  EXPECT_EQ(back.stamp, s.stamp);
  EXPECT_EQ(back.ranges.size(), 3u);
  EXPECT_FALSE(IsReturn(back.ranges[1]));
  EXPECT_EQ(back.ranges[2], 2.5f);
  EXPECT_EQ(back.angle_increment, 0.01f);
  EXPECT_EQ(back.sensor_pose.y, -0.2);
}

TEST(LcmConvertTest, RawOdometryAndSonarRoundTrip) {
  const OdometrySample o{FromSeconds(3.000001), Pose2{1, 2, -0.5}, 12.345, -6.789, 0.75, -0.125};
  const atlasd::odometry_t om = ToOdometryMessage(o);
  EXPECT_EQ(om.left_m, 12.345);
  EXPECT_EQ(om.right_m, -6.789);
  EXPECT_EQ(om.linear_velocity, 0.75);
  EXPECT_EQ(om.angular_velocity, -0.125);
  const OdometrySample ob = FromOdometryMessage(om);
  EXPECT_EQ(ob.stamp, o.stamp);
  EXPECT_EQ(ob.pose.theta, -0.5);
  EXPECT_EQ(ob.left_m, 12.345);
  EXPECT_EQ(ob.angular_velocity, -0.125);
  SonarReading r;
  r.stamp = FromSeconds(4.0);
  r.returns = {{3, 1.25f}, {7, kNoReturn}};
  const atlasd::sonar_t m = ToSonarMessage(r);
  EXPECT_EQ(m.num_returns, 2);
  const SonarReading rb = FromSonarMessage(m);
  ASSERT_EQ(rb.returns.size(), 2u);
  EXPECT_EQ(rb.returns[0].transducer, 3);
  EXPECT_EQ(rb.returns[0].range, 1.25f);
}

TEST(LcmConvertTest, DriverHealthKeepsCountersAndState) {
  DriverHealth h;
  h.device = "/dev/ttyUSB0";
  h.state = DriverState::kReconnecting;
  h.bad_crc = 7;
  h.garbage_bytes = 40;
  h.drops = 2;
  h.last_error = "gone";
  const atlasd::driver_health_t m = ToDriverHealthMessage("laser", h, 3, 8);
  EXPECT_EQ(m.name, "laser");
  EXPECT_EQ(m.state, 4);  // STATE_RECONNECTING (generated constants have no definition)
  EXPECT_EQ(m.bad_crc, 7);
  EXPECT_EQ(m.garbage_bytes, 40);
  EXPECT_EQ(m.queue_drops, 2);
  EXPECT_EQ(m.queue_depth, 3);
  EXPECT_EQ(m.queue_capacity, 8);
  EXPECT_EQ(m.last_error, "gone");
}

TEST(LcmConvertTest, GraphHypothesesAndPoseDescribeTheAtlas) {
  TestWorld w;
  Atlas atlas(TestWorld::Options(), w.Factory(), nullptr);
  for (int i = 0; i < 40; ++i) atlas.Step(Pose2{0.5, 0, 0}, TestScan());
  ASSERT_GT(atlas.Graph().FrameCount(), 1);  // the robot left the first frame's radius
  const Time t = FromSeconds(100.0);
  const atlasd::atlas_graph_t g = ToGraphMessage(t, atlas);
  EXPECT_EQ(g.utime, 100000000);
  EXPECT_EQ(g.num_frames, atlas.Graph().FrameCount());
  EXPECT_EQ(static_cast<int>(g.frames.size()), g.num_frames);
  EXPECT_EQ(g.num_edges, atlas.Graph().EdgeCount());
  const DominantOutput d = atlas.Dominant();
  ASSERT_TRUE(d.valid);
  EXPECT_EQ(g.dominant_frame_id, d.frame);
  // The dominant frame projects onto itself at the origin.
  EXPECT_TRUE(g.frames[d.frame].projected);
  EXPECT_NEAR(g.frames[d.frame].x, 0.0, 1e-12);
  for (const auto& e : g.edges) {
    EXPECT_GE(e.frame_from, 0);
    EXPECT_LT(e.frame_to, g.num_frames);
  }
  const atlasd::hypotheses_t h = ToHypothesesMessage(t, atlas);
  EXPECT_EQ(h.num_hypotheses, static_cast<int>(atlas.Hypotheses().size()));
  int dominant = 0;
  for (const auto& x : h.hypotheses) dominant += x.state == 2;
  EXPECT_EQ(dominant, 1);
  const atlasd::pose_t p = ToPoseMessage(t, d);
  EXPECT_EQ(p.frame_id, d.frame);
  EXPECT_DOUBLE_EQ(p.x, d.pose.mean.x);
  EXPECT_DOUBLE_EQ(p.covariance[4], d.pose.cov(1, 1));
  EXPECT_DOUBLE_EQ(p.q, d.q);
  EXPECT_EQ(p.hypothesis_id, d.hypothesis);
  EXPECT_EQ(p.switched, d.switched);
  DominantOutput switched = d;
  switched.switched = true;
  EXPECT_TRUE(ToPoseMessage(t, switched).switched);
  const atlasd::pose_t none = ToPoseMessage(t, DominantOutput{});
  EXPECT_EQ(none.hypothesis_id, -1);
  EXPECT_FALSE(none.switched);
  const atlasd::local_map_t m = ToLocalMapMessage(t, atlas);
  EXPECT_EQ(m.frame_id, d.frame);
  EXPECT_EQ(m.num_lines, static_cast<int>(m.lines.size()));
}

TEST(LcmConvertTest, PublisherSendsOnTheConfiguredChannelsWithEpochUtimeOverMemq) {
  lcm::LCM lcm("memq://");
  ASSERT_TRUE(lcm.good());
  LcmChannels channels;
  channels.pose = "TEST_POSE";
  const EpochClock epoch(1796166934000000);
  AtlasPublisher publisher(&lcm, channels, epoch);
  struct Handler {
    int count = 0;
    atlasd::pose_t last{};
    void On(const lcm::ReceiveBuffer*, const std::string&, const atlasd::pose_t* m) {
      ++count;
      last = *m;
    }
  } handler;
  lcm.subscribe("TEST_POSE", &Handler::On, &handler);
  DominantOutput d;
  d.valid = true;
  d.frame = 3;
  d.pose.mean = Pose2{1, 2, 0.5};
  d.q = 0.75;
  publisher.Pose(FromSeconds(1.5), d);
  ASSERT_EQ(lcm.handleTimeout(1000), 1);
  EXPECT_EQ(handler.count, 1);
  EXPECT_EQ(handler.last.frame_id, 3);
  // Microseconds since the epoch, and back to the stamp.
  EXPECT_EQ(handler.last.utime, 1796166934000000 + 1500000);
  EXPECT_EQ(epoch.Stamp(handler.last.utime), FromSeconds(1.5));
  EXPECT_DOUBLE_EQ(handler.last.q, 0.75);
  EXPECT_EQ(publisher.failures(), 0u);
}

}  // namespace
}  // namespace atlas
