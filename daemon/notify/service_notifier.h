#pragma once
// Tells systemd (Type=notify) how atlasd is doing, through sd_notify(3) on $NOTIFY_SOCKET.
//
// Contract (what atlasd's loop does with it):
// - Ready() once the devices are open and the loop is running (READY=1).
// - Watchdog() only while the loop is healthy, at least every WatchdogInterval()/2; systemd
//   kills and restarts a service whose pings stop for WatchdogSec.
// - Status(line) whenever the one-line summary changes (STATUS=...); newlines are replaced by
//   spaces so that a status can never inject another assignment.
// - Stopping() when shutdown begins (STOPPING=1).
// - ExtendTimeout(t) while a start waits on something outside atlasd (the multicast route):
//   systemd's start timeout is pushed to at least t from now (EXTEND_TIMEOUT_USEC=).
// Outside systemd ($NOTIFY_SOCKET unset) every call does nothing and says kNotUnderSystemd.
// Each call is one datagram, safe from any thread, never blocks for long (datagram socket).

#include <chrono>
#include <string_view>

namespace atlas {

enum class NotifyResult { kSent, kNotUnderSystemd, kFailed };

class ServiceNotifier {
 public:
  NotifyResult Ready();
  NotifyResult Watchdog();
  NotifyResult Status(std::string_view one_line);
  NotifyResult Stopping();
  NotifyResult ExtendTimeout(std::chrono::microseconds from_now);

  // The service's WatchdogSec when systemd expects pings from this process
  // ($WATCHDOG_USEC, with $WATCHDOG_PID naming this process); zero when no watchdog is set.
  static std::chrono::microseconds WatchdogInterval();

 private:
  NotifyResult Send(const char* state);
};

}  // namespace atlas
