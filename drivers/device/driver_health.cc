#include "drivers/device/driver_health.h"

namespace atlas {

const char* ToString(DriverState s) {
  switch (s) {
    case DriverState::kStopped:
      return "stopped";
    case DriverState::kConnecting:
      return "connecting";
    case DriverState::kRunning:
      return "running";
    case DriverState::kStalled:
      return "stalled";
    case DriverState::kReconnecting:
      return "reconnecting";
    case DriverState::kFailed:
      return "failed";
  }
  return "?";
}

void DriverHealthRecorder::SetError(std::string text) {
  std::lock_guard<std::mutex> lock(mutex_);
  last_error_ = std::move(text);
}

void DriverHealthRecorder::SetDeviceStatus(std::string text) {
  std::lock_guard<std::mutex> lock(mutex_);
  device_status_ = std::move(text);
}

void DriverHealthRecorder::CountMessage(Time now) {
  messages.fetch_add(1, std::memory_order_relaxed);
  if (window_start_ == Time{}) window_start_ = now;
  ++window_messages_;
  const double span = ToSeconds(now - window_start_);
  if (span >= 1.0) {
    rate_.store(static_cast<double>(window_messages_) / span, std::memory_order_relaxed);
    window_start_ = now;
    window_messages_ = 0;
  }
}

DriverHealth DriverHealthRecorder::Snapshot() const {
  DriverHealth h;
  h.device = device_;
  h.state = state();
  auto ld = [](const std::atomic<uint64_t>& a) { return a.load(std::memory_order_relaxed); };
  h.bytes = ld(bytes);
  h.messages = ld(messages);
  h.samples = ld(samples);
  h.bad_crc = ld(bad_crc);
  h.bad_length = ld(bad_length);
  h.garbage_bytes = ld(garbage_bytes);
  h.bad_messages = ld(bad_messages);
  h.truncated = ld(truncated);
  h.discontinuities = ld(discontinuities);
  h.error_frames = ld(error_frames);
  h.stalls = ld(stalls);
  h.disconnects = ld(disconnects);
  h.reconnects = ld(reconnects);
  h.connect_failures = ld(connect_failures);
  h.message_rate_hz = rate_.load(std::memory_order_relaxed);
  std::lock_guard<std::mutex> lock(mutex_);
  h.last_error = last_error_;
  h.device_status = device_status_;
  return h;
}

}  // namespace atlas
