#include "drivers/device/realtime_priority.h"

#include <pthread.h>
#include <sched.h>
#include <string.h>

namespace atlas {

std::string UseRealtimePriority(int priority) {
  sched_param p{};
  p.sched_priority = priority;
  const int err = pthread_setschedparam(pthread_self(), SCHED_FIFO, &p);
  if (err == 0) return "";
  return "SCHED_FIFO priority " + std::to_string(priority) + " refused (" + strerror(err) + ")";
}

}  // namespace atlas
