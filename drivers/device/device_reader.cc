#include "drivers/device/device_reader.h"

#include <algorithm>
#include <exception>

#include "drivers/device/realtime_priority.h"

namespace atlas {

std::string ReconnectOptions::Validate() const {
  if (initial_backoff <= Duration::zero()) return "reconnect: initial_backoff must be > 0";
  if (max_backoff < initial_backoff) return "reconnect: max_backoff must be >= initial_backoff";
  if (max_attempts < 0) return "reconnect: max_attempts must be >= 0";
  if (stall_timeout <= Duration::zero()) return "reconnect: stall_timeout must be > 0";
  if (realtime_priority < 0 || realtime_priority > 99)
    return "reconnect: realtime_priority must be 0 (off) or 1..99";
  if (reopen_after_silence < stall_timeout)
    return "reconnect: reopen_after_silence must be >= stall_timeout";
  return "";
}

Duration BackoffDelay(const ReconnectOptions& options, int failures) {
  Duration d = options.initial_backoff;
  for (int i = 1; i < failures && d < options.max_backoff; ++i) d *= 2;
  return std::min(d, options.max_backoff);
}

DeviceReader::DeviceReader(std::string device, const ReconnectOptions& options)
    : health_(device), reconnect_(options), log_(device) {}

DeviceReader::~DeviceReader() { Stop(); }

void DeviceReader::Start() {
  if (thread_.joinable()) return;
  stop_.store(false, std::memory_order_release);
  thread_ = std::thread([this] {
    // Nothing a device sends throws; what is left (out of memory) stops this reader, said in
    // its health, instead of terminating atlasd.
    try {
      Loop();
    } catch (const std::exception& e) {
      const std::string why = std::string("the reader stopped: ") + e.what();
      health_.SetError(why);
      health_.SetState(DriverState::kFailed);
      Say(log_.GaveUp(why));
    }
  });
}

void DeviceReader::Stop() {
  {
    std::lock_guard<std::mutex> lock(sleep_mutex_);
    stop_.store(true, std::memory_order_release);
  }
  sleep_cv_.notify_all();
  if (thread_.joinable()) thread_.join();
}

DriverHealth DeviceReader::Health() const {
  DriverHealth h = health_.Snapshot();
  h.drops = QueueDrops();
  return h;
}

bool DeviceReader::SleepFor(Duration d) {
  std::unique_lock<std::mutex> lock(sleep_mutex_);
  return !sleep_cv_.wait_for(lock, d, [this] { return Stopping(); });
}

bool DeviceReader::TrackSilence(bool got_data, Time now) {
  if (health_.messages.load(std::memory_order_relaxed) > session_start_messages_)
    Say(log_.Delivering());
  if (got_data || last_data_ == Time{}) {
    last_data_ = now;
    if (stalled_) {
      health_.SetState(DriverState::kRunning);
      Say(log_.Resumed());
    }
    stalled_ = false;
    return false;
  }
  const Duration silent = now - last_data_;
  if (!stalled_ && silent >= reconnect_.stall_timeout) {
    stalled_ = true;
    health_.stalls.fetch_add(1, std::memory_order_relaxed);
    health_.SetState(DriverState::kStalled);
    const std::string why = "no data for " + std::to_string(ToSeconds(silent)).substr(0, 4) + " s";
    health_.SetError(why);
    Say(log_.Stalled(why));
  }
  return silent >= reconnect_.reopen_after_silence;
}

void DeviceReader::Loop() {
  if (reconnect_.realtime_priority > 0) {
    if (std::string why = UseRealtimePriority(reconnect_.realtime_priority); !why.empty()) {
      why += ": running at normal priority";
      health_.SetError(why);
      ReportCondition(LogPriority::kWarning, why);
    }
  }
  Say(log_.Connecting());
  int failures = 0;  // consecutive attempts without data (see BackoffDelay)
  bool ever_connected = false;
  while (!Stopping()) {
    health_.SetState(ever_connected ? DriverState::kReconnecting : DriverState::kConnecting);
    std::string error;
    const uint64_t messages_before = health_.messages.load(std::memory_order_relaxed);
    if (!Connect(&error)) {
      Disconnect();
      ++failures;
      health_.connect_failures.fetch_add(1, std::memory_order_relaxed);
      health_.SetError(error);
      if (reconnect_.max_attempts > 0 && failures >= reconnect_.max_attempts) {
        health_.SetState(DriverState::kFailed);
        Say(log_.GaveUp(error + " (" + std::to_string(failures) + " attempts)"));
        return;
      }
      Say(log_.AttemptFailed(error));
      if (!BackoffSleep(BackoffDelay(reconnect_, failures))) break;
      continue;
    }
    if (ever_connected) health_.reconnects.fetch_add(1, std::memory_order_relaxed);
    ever_connected = true;
    last_data_ = Time{};
    stalled_ = false;
    session_start_messages_ = messages_before;
    health_.SetState(DriverState::kRunning);
    const SessionEnd end = ReadUntilGone(&error);
    Disconnect();
    if (end == SessionEnd::kStopped) break;
    health_.disconnects.fetch_add(1, std::memory_order_relaxed);
    health_.SetError(error);
    health_.SetState(DriverState::kReconnecting);
    // A session that delivered is said lost; one that ended before its first message is a
    // failed attempt, said once per reason like a failed open (DriverLog::Lost).
    if (health_.messages.load(std::memory_order_relaxed) > messages_before) Say(log_.Delivering());
    Say(log_.Lost(error));
    // Only a session that delivered data starts the backoff again from initial_backoff; one
    // that opened and died at once is a failure like a failed open, so the backoff grows.
    if (health_.messages.load(std::memory_order_relaxed) > messages_before) failures = 0;
    ++failures;
    if (!BackoffSleep(BackoffDelay(reconnect_, failures))) break;
  }
  health_.SetState(DriverState::kStopped);
  Say(log_.Stopped());
}

}  // namespace atlas
