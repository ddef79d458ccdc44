#include <gtest/gtest.h>
#include <lcm/lcm-cpp.hpp>

#include <cmath>
#include <limits>
#include <vector>

#include "atlas/laser_scan_t.hpp"
#include "atlas/odometry_t.hpp"
#include "atlas/pose_t.hpp"
#include "atlas/sonar_t.hpp"

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
  atlas::laser_scan_t s;
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

TEST(LcmTypes, PoseOdometrySonarRoundTrip) {
  atlas::pose_t p{};
  p.frame_id = 7;
  p.x = 1.5;
  p.covariance[4] = 0.25;
  p.q = 0.9;
  const auto po = RoundTrip(p);
  EXPECT_EQ(po.frame_id, 7);
  EXPECT_DOUBLE_EQ(po.covariance[4], 0.25);

  atlas::odometry_t o{};
  o.left_m = 12.345;
  EXPECT_DOUBLE_EQ(RoundTrip(o).left_m, 12.345);

  atlas::sonar_t s{};
  s.num_returns = 2;
  s.transducer = {3, 15};
  s.range = {0.5f, 4.0f};
  const auto so = RoundTrip(s);
  ASSERT_EQ(so.num_returns, 2);
  EXPECT_EQ(so.transducer[1], 15);
}

TEST(LcmTypes, PublishAndReceiveInProcess) {
  lcm::LCM lcm("memq://");
  ASSERT_TRUE(lcm.good());
  struct Handler {
    int got = 0;
    int frame = -1;
    void On(const lcm::ReceiveBuffer*, const std::string&, const atlas::pose_t* m) {
      ++got;
      frame = m->frame_id;
    }
  } h;
  lcm.subscribe("ATLAS_POSE", &Handler::On, &h);
  atlas::pose_t p{};
  p.frame_id = 42;
  ASSERT_EQ(lcm.publish("ATLAS_POSE", &p), 0);
  ASSERT_GT(lcm.handleTimeout(1000), 0);
  EXPECT_EQ(h.got, 1);
  EXPECT_EQ(h.frame, 42);
}

}  // namespace
