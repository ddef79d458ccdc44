#include "daemon/atlasd/live_timing.h"

#include <algorithm>

namespace atlas {

Duration SecondsToDuration(double seconds) {
  return std::chrono::duration_cast<Duration>(std::chrono::duration<double>(seconds));
}

WatchdogTiming WatchdogTimingFor(std::chrono::microseconds watchdog_interval) {
  WatchdogTiming t;
  t.ping_period = watchdog_interval.count() > 0
                      ? std::chrono::duration_cast<Duration>(watchdog_interval / 2)
                      : Duration(std::chrono::seconds(1));
  t.heartbeat_max = std::min<Duration>(t.ping_period, std::chrono::seconds(1));
  return t;
}

bool ReadyNow(bool loop_running, const std::vector<DriverEntry>& drivers, Time now, Time deadline,
              bool* all_running) {
  bool all = loop_running;
  for (const DriverEntry& d : drivers) all = all && d.health.state == DriverState::kRunning;
  *all_running = all;
  return all || now >= deadline;
}

Duration HealthLinePeriod(double line_period_s, double health_period_s) {
  return SecondsToDuration(line_period_s > 0 ? line_period_s : health_period_s) -
         std::chrono::milliseconds(5);
}

}  // namespace atlas
