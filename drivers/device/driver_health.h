#pragma once
// The health of one device driver as the daemon reports it: the connection state, counters of
// everything that went through or went wrong, the last error in plain words and the message
// rate. DriverHealthRecorder is written by the reader thread and read (as a DriverHealth
// snapshot) by any thread: counters are atomics, the texts are under a mutex.

#include <atomic>
#include <cstdint>
#include <mutex>
#include <string>

#include "core/common/time.h"

namespace atlas {

enum class DriverState {
  kStopped,       // not started, or stopped cleanly
  kConnecting,    // first open and start-up sequence
  kRunning,       // data flowing
  kStalled,       // connected but silent for longer than the stall timeout
  kReconnecting,  // the device went away; reopening with capped backoff
  kFailed,        // gave up (only with a finite attempt budget)
};
const char* ToString(DriverState s);

struct DriverHealth {
  std::string device;
  DriverState state = DriverState::kStopped;
  uint64_t bytes = 0;             // bytes (or frames' payload bytes) received
  uint64_t messages = 0;          // good messages decoded (scans, 0x311 frames, SIPs)
  uint64_t samples = 0;           // samples pushed into the queue
  uint64_t bad_crc = 0;           // CRC / checksum failures
  uint64_t bad_length = 0;        // impossible LEN / N fields
  uint64_t garbage_bytes = 0;     // bytes outside any valid message
  uint64_t bad_messages = 0;      // well-framed but undecodable (bad count word, bad DLC, ...)
  uint64_t truncated = 0;         // partial messages abandoned after a silent gap
  uint64_t discontinuities = 0;   // odometry counter jumps skipped
  uint64_t error_frames = 0;      // CAN error frames
  uint64_t stalls = 0;            // silences longer than the stall timeout
  uint64_t disconnects = 0;       // the device went away while running
  uint64_t reconnects = 0;        // successful reopen after a disconnect
  uint64_t connect_failures = 0;  // failed open / start-up attempts
  uint64_t drops = 0;             // samples dropped because the queue was full (oldest first)
  std::string last_error;         // empty if none yet
  std::string device_status;      // what the device says of itself (scanner status, ...)
  double message_rate_hz = 0.0;   // over the last second or so
};

class DriverHealthRecorder {
 public:
  explicit DriverHealthRecorder(std::string device) : device_(std::move(device)) {}

  std::atomic<uint64_t> bytes{0}, messages{0}, samples{0}, bad_crc{0}, bad_length{0},
      garbage_bytes{0}, bad_messages{0}, truncated{0}, discontinuities{0}, error_frames{0},
      stalls{0}, disconnects{0}, reconnects{0}, connect_failures{0};

  void SetState(DriverState s) { state_.store(s, std::memory_order_release); }
  DriverState state() const { return state_.load(std::memory_order_acquire); }
  void SetError(std::string text);
  void SetDeviceStatus(std::string text);
  // Called by the reader thread once per message; refreshes the rate about once a second.
  void CountMessage(Time now);
  // Snapshot; `drops` is filled in by the owner of the queue.
  DriverHealth Snapshot() const;

 private:
  std::string device_;
  std::atomic<DriverState> state_{DriverState::kStopped};
  std::atomic<double> rate_{0.0};
  Time window_start_{};
  uint64_t window_messages_ = 0;
  mutable std::mutex mutex_;
  std::string last_error_;
  std::string device_status_;
};

}  // namespace atlas
