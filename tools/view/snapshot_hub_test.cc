#include "tools/view/snapshot_hub.h"

#include <gtest/gtest.h>

#include <thread>

namespace atlas::view {
namespace {

TEST(SnapshotHub, OpensAtMostMaxStreams) {
  SnapshotHub hub(2);
  EXPECT_TRUE(hub.TryOpenStream());
  EXPECT_TRUE(hub.TryOpenStream());
  EXPECT_FALSE(hub.TryOpenStream());
  EXPECT_EQ(hub.streams(), 2);
  hub.CloseStream();
  EXPECT_TRUE(hub.TryOpenStream());
  hub.Stop();
  hub.CloseStream();
  EXPECT_FALSE(hub.TryOpenStream());
}

TEST(SnapshotHub, WaitersGetTheLatestUpdateOnly) {
  SnapshotHub hub(1);
  uint64_t seen = 0;
  EXPECT_EQ(hub.WaitNewer(&seen, std::chrono::milliseconds(1)), nullptr);
  hub.Publish("a");
  hub.Publish("b");  // "a" is never seen: nothing queues up
  auto u = hub.WaitNewer(&seen, std::chrono::milliseconds(1));
  ASSERT_NE(u, nullptr);
  EXPECT_EQ(*u, "b");
  EXPECT_EQ(seen, 2u);
  EXPECT_EQ(hub.WaitNewer(&seen, std::chrono::milliseconds(1)), nullptr);
}

TEST(SnapshotHub, PublishAndStopWakeAWaiter) {
  SnapshotHub hub(1);
  uint64_t seen = 0;
  std::thread publisher([&] {
    std::this_thread::sleep_for(std::chrono::milliseconds(20));
    hub.Publish("x");
  });
  auto u = hub.WaitNewer(&seen, std::chrono::seconds(10));
  publisher.join();
  ASSERT_NE(u, nullptr);
  EXPECT_EQ(*u, "x");

  const Time t0 = Now();
  std::thread stopper([&] {
    std::this_thread::sleep_for(std::chrono::milliseconds(20));
    hub.Stop();
  });
  EXPECT_EQ(hub.WaitNewer(&seen, std::chrono::seconds(10)), nullptr);
  stopper.join();
  EXPECT_LT(Now() - t0, std::chrono::seconds(5));
  EXPECT_TRUE(hub.stopped());
}

TEST(RateGate, SaysYesAtMostOncePerPeriod) {
  RateGate gate(std::chrono::milliseconds(250));
  const Time t0 = FromSeconds(100);
  EXPECT_TRUE(gate.Due(t0));
  EXPECT_FALSE(gate.Due(t0 + std::chrono::milliseconds(100)));
  EXPECT_FALSE(gate.Due(t0 + std::chrono::milliseconds(249)));
  EXPECT_TRUE(gate.Due(t0 + std::chrono::milliseconds(250)));
  EXPECT_FALSE(gate.Due(t0 + std::chrono::milliseconds(400)));
  // Over 10 s of calls every 10 ms, 40 updates: 4 per second.
  RateGate g(std::chrono::milliseconds(250));
  int yes = 0;
  for (int i = 0; i < 1000; ++i) yes += g.Due(t0 + std::chrono::milliseconds(10 * i));
  EXPECT_EQ(yes, 40);
}

}  // namespace
}  // namespace atlas::view
