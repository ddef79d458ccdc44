#include "drivers/device/realtime_priority.h"

#include <gtest/gtest.h>
#include <pthread.h>
#include <sched.h>

#include <thread>

namespace atlas {
namespace {

// Priority 100 is outside SCHED_FIFO's range for every caller, root or not: refused, said, and
// the thread keeps its scheduling.
TEST(RealtimePriority, AnOutOfRangePriorityIsRefusedAndSaid) {
  std::string why;
  int policy = -1;
  std::thread t([&] {
    why = UseRealtimePriority(100);
    sched_param p{};
    pthread_getschedparam(pthread_self(), &policy, &p);
  });
  t.join();
  EXPECT_EQ(why.rfind("SCHED_FIFO priority 100 refused (", 0), 0u) << why;
  EXPECT_EQ(policy, SCHED_OTHER);
}

}  // namespace
}  // namespace atlas
