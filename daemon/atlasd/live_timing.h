#pragma once
// When the live daemon's threads act (live_daemon.h): periods, the watchdog's ping period and
// the heartbeat that gates it, and readiness. Arithmetic only; the threads read the clock.

#include <chrono>
#include <cstdint>
#include <vector>

#include "core/common/time.h"
#include "daemon/atlasd/health_report.h"

namespace atlas {

// A configured period in seconds as a Duration (truncated to whole nanoseconds).
Duration SecondsToDuration(double seconds);

// True when `period` has passed since `last`.
inline bool Due(Time now, Time last, Duration period) { return now - last >= period; }

// systemd's watchdog (ServiceNotifier::WatchdogInterval(), zero when none is set): the main
// thread pings at half the interval (every second without a watchdog, for STATUS=), and only
// while the loop thread's heartbeat is younger than heartbeat_max (the ping period, at most 1 s).
struct WatchdogTiming {
  Duration ping_period{};
  Duration heartbeat_max{};
};
WatchdogTiming WatchdogTimingFor(std::chrono::microseconds watchdog_interval);

// The loop thread's heartbeat (nanoseconds since the clock's epoch) is fresh at `now`.
inline bool HeartbeatFresh(Time now, int64_t heartbeat_ns, Duration heartbeat_max) {
  return now - Time(Duration(heartbeat_ns)) < heartbeat_max;
}

// READY=1 once the loop runs and every device's reader is running, or at the deadline
// (a missing device is a fault atlasd reports and survives). `all_running` says which.
bool ReadyNow(bool loop_running, const std::vector<DriverEntry>& drivers, Time now, Time deadline,
              bool* all_running);

// The health line on stderr: every `line_period_s` (flag; 0: every health period), checked at
// each health message, with 5 ms of slack for the loop's wake-up jitter.
Duration HealthLinePeriod(double line_period_s, double health_period_s);

}  // namespace atlas
