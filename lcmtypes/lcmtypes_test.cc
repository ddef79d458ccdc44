#include <gtest/gtest.h>

#include <cmath>
#include <lcm/lcm-cpp.hpp>
#include <limits>
#include <vector>

#include "atlasd/atlas_graph_t.hpp"
#include "atlasd/health_t.hpp"
#include "atlasd/hypotheses_t.hpp"
#include "atlasd/laser_scan_t.hpp"
#include "atlasd/local_map_t.hpp"
#include "atlasd/odometry_t.hpp"
#include "atlasd/pose_t.hpp"
#include "atlasd/reference_pose_t.hpp"
#include "atlasd/sonar_t.hpp"

namespace {

template <typename T>
T RoundTrip(const T& in) {
  std::vector<uint8_t> buf(in.getEncodedSize());
  EXPECT_EQ(in.encode(buf.data(), 0, static_cast<int>(buf.size())), static_cast<int>(buf.size()));
  T out;
  EXPECT_EQ(out.decode(buf.data(), 0, static_cast<int>(buf.size())), static_cast<int>(buf.size()));
  return out;
}

TEST(LcmTypes, LaserScanRoundTripKeepsNoReturn) {
  atlasd::laser_scan_t s;
  s.utime = 123456789;
  s.angle_min = -1.5707963f;
  s.angle_increment = 0.0087266f;
  s.max_range = 81.91f;
  s.ranges = {1.0f, std::numeric_limits<float>::infinity(), 2.5f};
  s.num_ranges = 3;
  s.sensor_x = 0.1;
  s.sensor_y = 0;
  s.sensor_theta = 0;
  const auto out = RoundTrip(s);
  EXPECT_EQ(out.utime, s.utime);
  ASSERT_EQ(out.num_ranges, 3);
  EXPECT_FLOAT_EQ(out.ranges[2], 2.5f);
  EXPECT_TRUE(std::isinf(out.ranges[1]));
}

TEST(LcmTypes, PoseReferencePoseOdometrySonarRoundTrip) {
  atlasd::pose_t p{};
  p.frame_id = 7;
  p.x = 1.5;
  p.covariance[4] = 0.25;
  p.q = 0.9;
  const auto po = RoundTrip(p);
  EXPECT_EQ(po.frame_id, 7);
  EXPECT_DOUBLE_EQ(po.covariance[4], 0.25);

  atlasd::reference_pose_t r{};
  r.reference_frame_id = 0;
  r.placed = true;
  r.frame_id = 7;
  r.x = -3.5;
  r.frame_covariance[8] = 0.01;
  r.hops = 4;
  const auto ro = RoundTrip(r);
  EXPECT_TRUE(ro.placed);
  EXPECT_EQ(ro.frame_id, 7);
  EXPECT_DOUBLE_EQ(ro.x, -3.5);
  EXPECT_DOUBLE_EQ(ro.frame_covariance[8], 0.01);
  EXPECT_EQ(ro.hops, 4);

  atlasd::odometry_t o{};
  o.left_m = 12.345;
  EXPECT_DOUBLE_EQ(RoundTrip(o).left_m, 12.345);

  atlasd::sonar_t s{};
  s.num_returns = 2;
  s.transducer = {3, 15};
  s.range = {0.5f, 4.0f};
  const auto so = RoundTrip(s);
  ASSERT_EQ(so.num_returns, 2);
  EXPECT_EQ(so.transducer[1], 15);
}

TEST(LcmTypes, LocalMapRoundTrip) {
  atlasd::local_map_t m{};
  m.utime = 99;
  m.frame_id = 3;
  m.capacity = 30;
  m.robot_theta = -0.5;
  for (int i = 0; i < 2; ++i) {
    atlasd::line_segment_t l{};
    l.id = 10 + i;
    l.rho = 1.0 + i;
    l.alpha = -3.0 + i;
    l.covariance[3] = 0.01 * (i + 1);
    l.x1 = 4.5;
    m.lines.push_back(l);
  }
  m.num_lines = 2;
  const auto out = RoundTrip(m);
  EXPECT_EQ(out.frame_id, 3);
  EXPECT_DOUBLE_EQ(out.robot_theta, -0.5);
  ASSERT_EQ(out.num_lines, 2);
  EXPECT_EQ(out.lines[1].id, 11);
  EXPECT_DOUBLE_EQ(out.lines[1].rho, 2.0);
  EXPECT_DOUBLE_EQ(out.lines[1].alpha, -2.0);
  EXPECT_DOUBLE_EQ(out.lines[1].covariance[3], 0.02);
  EXPECT_DOUBLE_EQ(out.lines[0].x1, 4.5);
}

TEST(LcmTypes, AtlasGraphRoundTrip) {
  atlasd::atlas_graph_t g{};
  g.step = 1234;
  g.dominant_frame_id = 1;
  for (int i = 0; i < 3; ++i) {
    atlasd::atlas_frame_t f{};
    f.id = i;
    f.num_features = 5 * i;
    f.projected = i != 2;
    f.x = i * 10.0;
    g.frames.push_back(f);
  }
  g.num_frames = 3;
  atlasd::atlas_edge_t e{};
  e.frame_from = 0;
  e.frame_to = 1;
  e.x = 9.5;
  e.theta = 0.1;
  e.covariance[8] = 0.003;
  e.kind = atlasd::atlas_edge_t::KIND_REFINED;
  e.origin = atlasd::atlas_edge_t::KIND_MAP_MATCH;
  e.refinements = 4;
  g.edges.push_back(e);
  g.num_edges = 1;
  const auto out = RoundTrip(g);
  EXPECT_EQ(out.step, 1234);
  EXPECT_EQ(out.dominant_frame_id, 1);
  ASSERT_EQ(out.num_frames, 3);
  EXPECT_EQ(out.frames[2].num_features, 10);
  EXPECT_FALSE(out.frames[2].projected);
  EXPECT_TRUE(out.frames[1].projected);
  ASSERT_EQ(out.num_edges, 1);
  EXPECT_EQ(out.edges[0].frame_to, 1);
  EXPECT_DOUBLE_EQ(out.edges[0].covariance[8], 0.003);
  EXPECT_EQ(out.edges[0].kind, 2);
  EXPECT_EQ(out.edges[0].origin, 1);
  EXPECT_EQ(out.edges[0].refinements, 4);
}

TEST(LcmTypes, HypothesesRoundTrip) {
  atlasd::hypotheses_t h{};
  h.dominant_id = 17;
  const int8_t states[] = {atlasd::hypothesis_t::STATE_JUVENILE, atlasd::hypothesis_t::STATE_DOMINANT,
                           atlasd::hypothesis_t::STATE_RETIRED};
  for (int i = 0; i < 3; ++i) {
    atlasd::hypothesis_t x{};
    x.id = 16 + i;
    x.frame_id = i;
    x.state = states[i];
    x.q = 0.25 * i;
    x.covariance[0] = 0.5;
    h.hypotheses.push_back(x);
  }
  h.num_hypotheses = 3;
  const auto out = RoundTrip(h);
  EXPECT_EQ(out.dominant_id, 17);
  ASSERT_EQ(out.num_hypotheses, 3);
  EXPECT_EQ(out.hypotheses[1].state, 2);  // STATE_DOMINANT
  EXPECT_EQ(out.hypotheses[2].state, 3);
  EXPECT_DOUBLE_EQ(out.hypotheses[2].q, 0.5);
  EXPECT_DOUBLE_EQ(out.hypotheses[0].covariance[0], 0.5);
}

TEST(LcmTypes, HealthRoundTrip) {
  atlasd::health_t h{};
  h.steps = 5000;
  h.period_steps = 75;
  h.step_time_median_us = 420.5f;
  h.step_time_p99_us = 1900.0f;
  h.overruns = 2;
  h.resident_memory_bytes = int64_t{3} << 30;
  h.status = "ok: 12 frames";
  h.version = "0.1.0 (git 990180e)";
  atlasd::driver_health_t laser{};
  laser.name = "laser";
  laser.device = "/dev/ttyUSB0";
  laser.state = atlasd::driver_health_t::STATE_RECONNECTING;
  laser.queue_depth = 3;
  laser.queue_capacity = 8;
  laser.queue_drops = 1;
  laser.bad_crc = 7;
  laser.last_error = "read: device went away";
  atlasd::driver_health_t odometry{};
  odometry.name = "odometry";
  odometry.discontinuities = 1;
  h.drivers = {laser, odometry};
  h.num_drivers = 2;
  const auto out = RoundTrip(h);
  EXPECT_EQ(out.steps, 5000);
  EXPECT_FLOAT_EQ(out.step_time_p99_us, 1900.0f);
  EXPECT_EQ(out.resident_memory_bytes, int64_t{3} << 30);
  EXPECT_EQ(out.status, "ok: 12 frames");
  EXPECT_EQ(out.version, "0.1.0 (git 990180e)");
  ASSERT_EQ(out.num_drivers, 2);
  EXPECT_EQ(out.drivers[0].state, 4);
  EXPECT_EQ(out.drivers[0].bad_crc, 7);
  EXPECT_EQ(out.drivers[0].last_error, "read: device went away");
  EXPECT_EQ(out.drivers[1].name, "odometry");
  EXPECT_EQ(out.drivers[1].discontinuities, 1);
}

TEST(LcmTypes, PublishAndReceiveInProcess) {
  lcm::LCM lcm("memq://");
  ASSERT_TRUE(lcm.good());
  struct Handler {
    int got = 0;
    int frame = -1;
    void On(const lcm::ReceiveBuffer*, const std::string&, const atlasd::pose_t* m) {
      ++got;
      frame = m->frame_id;
    }
  } h;
  lcm.subscribe("ATLAS_POSE", &Handler::On, &h);
  atlasd::pose_t p{};
  p.frame_id = 42;
  ASSERT_EQ(lcm.publish("ATLAS_POSE", &p), 0);
  ASSERT_GT(lcm.handleTimeout(1000), 0);
  EXPECT_EQ(h.got, 1);
  EXPECT_EQ(h.frame, 42);
}

}  // namespace
