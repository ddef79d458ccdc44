#include "daemon/notify/service_notifier.h"

#include <systemd/sd-daemon.h>

#include <string>

namespace atlas {

NotifyResult ServiceNotifier::Send(const char* state) {
  const int r = sd_notify(0, state);
  if (r > 0) return NotifyResult::kSent;
  return r == 0 ? NotifyResult::kNotUnderSystemd : NotifyResult::kFailed;
}

NotifyResult ServiceNotifier::Ready() { return Send("READY=1"); }

NotifyResult ServiceNotifier::Watchdog() { return Send("WATCHDOG=1"); }

NotifyResult ServiceNotifier::Stopping() { return Send("STOPPING=1"); }

NotifyResult ServiceNotifier::ExtendTimeout(std::chrono::microseconds from_now) {
  return Send(("EXTEND_TIMEOUT_USEC=" + std::to_string(from_now.count())).c_str());
}

NotifyResult ServiceNotifier::Status(std::string_view one_line) {
  std::string state = "STATUS=";
  state.reserve(state.size() + one_line.size());
  for (char c : one_line) state.push_back(c == '\n' || c == '\r' ? ' ' : c);
  return Send(state.c_str());
}

std::chrono::microseconds ServiceNotifier::WatchdogInterval() {
  uint64_t usec = 0;
  if (sd_watchdog_enabled(0, &usec) > 0) return std::chrono::microseconds(usec);
  return std::chrono::microseconds(0);
}

}  // namespace atlas
