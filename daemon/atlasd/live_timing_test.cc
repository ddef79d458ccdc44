#include "daemon/atlasd/live_timing.h"

#include <gtest/gtest.h>

namespace atlas {
namespace {

using std::chrono::microseconds;
using std::chrono::milliseconds;
using std::chrono::seconds;

TEST(LiveTiming, SecondsToDurationTruncatesToNanoseconds) {
  EXPECT_EQ(SecondsToDuration(0.5), milliseconds(500));
  EXPECT_EQ(SecondsToDuration(2.0), seconds(2));
  EXPECT_EQ(SecondsToDuration(1.5e-9), Duration(1));
  EXPECT_EQ(SecondsToDuration(0.0), Duration::zero());
}

TEST(LiveTiming, DueOncePeriodHasPassed) {
  const Time last = Time(seconds(10));
  EXPECT_FALSE(Due(last + milliseconds(999), last, seconds(1)));
  EXPECT_TRUE(Due(last + seconds(1), last, seconds(1)));
  EXPECT_TRUE(Due(last + seconds(5), last, seconds(1)));
  // Never run yet: due at once.
  EXPECT_TRUE(Due(Time(seconds(1)), Time{}, seconds(1)));
}

// Pings at half the watchdog interval; the heartbeat gate is the ping period, at most 1 s.
TEST(LiveTiming, WatchdogPingsAtHalfTheInterval) {
  const WatchdogTiming w = WatchdogTimingFor(seconds(10));
  EXPECT_EQ(w.ping_period, seconds(5));
  EXPECT_EQ(w.heartbeat_max, seconds(1));
  const WatchdogTiming fast = WatchdogTimingFor(milliseconds(600));
  EXPECT_EQ(fast.ping_period, milliseconds(300));
  EXPECT_EQ(fast.heartbeat_max, milliseconds(300));
  const WatchdogTiming none = WatchdogTimingFor(microseconds(0));
  EXPECT_EQ(none.ping_period, seconds(1));
  EXPECT_EQ(none.heartbeat_max, seconds(1));
}

TEST(LiveTiming, HeartbeatIsFreshForLessThanItsLimit) {
  const Time beat = Time(seconds(100));
  const int64_t ns = beat.time_since_epoch().count();
  EXPECT_TRUE(HeartbeatFresh(beat + milliseconds(999), ns, seconds(1)));
  EXPECT_FALSE(HeartbeatFresh(beat + seconds(1), ns, seconds(1)));
  // No heartbeat yet (0): stale.
  EXPECT_FALSE(HeartbeatFresh(beat, 0, seconds(1)));
}

TEST(LiveTiming, ReadyWhenEverythingRunsOrAtTheDeadline) {
  std::vector<DriverEntry> drivers(2);
  drivers[0].health.state = DriverState::kRunning;
  drivers[1].health.state = DriverState::kConnecting;
  const Time deadline = Time(seconds(5));
  bool all = true;
  EXPECT_FALSE(ReadyNow(true, drivers, Time(seconds(1)), deadline, &all));
  EXPECT_FALSE(all);
  EXPECT_TRUE(ReadyNow(true, drivers, deadline, deadline, &all));
  EXPECT_FALSE(all);  // ready without every device
  drivers[1].health.state = DriverState::kRunning;
  EXPECT_FALSE(ReadyNow(false, drivers, Time(seconds(1)), deadline, &all));
  EXPECT_TRUE(ReadyNow(true, drivers, Time(seconds(1)), deadline, &all));
  EXPECT_TRUE(all);
}

TEST(LiveTiming, HealthLineEveryFlagPeriodOrHealthPeriod) {
  EXPECT_EQ(HealthLinePeriod(0.0, 1.0), milliseconds(995));
  EXPECT_EQ(HealthLinePeriod(10.0, 1.0), milliseconds(9995));
}

}  // namespace
}  // namespace atlas
