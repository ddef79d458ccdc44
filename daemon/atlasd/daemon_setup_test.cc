#include "daemon/atlasd/daemon_setup.h"

#include <gtest/gtest.h>

namespace atlas {
namespace {

// The driver threads are on the pose's latency path: with a real-time loop they run SCHED_FIFO
// at the loop's priority, and at normal priority otherwise.
TEST(DaemonSetup, DriverThreadsFollowTheLoopsRealTimePriority) {
  DaemonOptions o;
  EXPECT_EQ(ToLaserReaderOptions(o).reconnect.realtime_priority, 0);
  EXPECT_EQ(ToOdometryReaderOptions(o).reconnect.realtime_priority, 0);
  EXPECT_EQ(ToSonarReaderOptions(o).reconnect.realtime_priority, 0);
  for (SchedPolicy policy : {SchedPolicy::kFifo, SchedPolicy::kRoundRobin}) {
    o.scheduling.policy = policy;
    o.scheduling.priority = 37;
    EXPECT_EQ(ToLaserReaderOptions(o).reconnect.realtime_priority, 37);
    EXPECT_EQ(ToOdometryReaderOptions(o).reconnect.realtime_priority, 37);
    EXPECT_EQ(ToSonarReaderOptions(o).reconnect.realtime_priority, 37);
  }
  EXPECT_EQ(ValidateDerivedOptions(o), "");
}

}  // namespace
}  // namespace atlas
