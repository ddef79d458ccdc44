#include <gtest/gtest.h>
#include <stdlib.h>
#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <filesystem>

#include "drivers/agilex/wheel_odometry.h"
#include "drivers/can/can_transport.h"
#include "drivers/fake/fake_agilex_base.h"
#include "drivers/fake/fake_can_bus.h"
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
