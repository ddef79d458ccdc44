#pragma once
// Between the thread that builds page updates and the event streams that send them: the latest
// update only (a slow browser skips updates, nothing queues up), a fixed number of streams, and
// the rate limit. Thread-safe; no sockets.

#include <condition_variable>
#include <cstdint>
#include <memory>
#include <mutex>
#include <string>

#include "core/common/time.h"

namespace atlas::view {

class SnapshotHub {
 public:
  explicit SnapshotHub(int max_streams) : max_streams_(max_streams) {}

  // A stream slot: false when `max_streams` are open (the client gets 503) or after Stop().
  bool TryOpenStream();
  void CloseStream();
  int streams() const;

  // Makes `json` the latest update and wakes the streams.
  void Publish(std::string json);
  // The latest update and its sequence number (0 and nullptr before the first).
  std::shared_ptr<const std::string> Latest(uint64_t* seq) const;
  // Waits up to `timeout` for an update newer than `*seen`; returns it and sets `*seen`, or
  // nullptr on timeout or after Stop().
  std::shared_ptr<const std::string> WaitNewer(uint64_t* seen, Duration timeout);

  void Stop();
  bool stopped() const;

 private:
  const int max_streams_;
  mutable std::mutex mu_;
  std::condition_variable cv_;
  std::shared_ptr<const std::string> latest_;
  uint64_t seq_ = 0;
  int streams_ = 0;
  bool stopped_ = false;
};

// At most one "yes" per period: Due(now) is true when no earlier call said yes within `period`.
class RateGate {
 public:
  explicit RateGate(Duration period) : period_(period) {}
  bool Due(Time now) {
    if (said_yes_ && now - last_ < period_) return false;
    said_yes_ = true;
    last_ = now;
    return true;
  }

 private:
  Duration period_;
  Time last_{};
  bool said_yes_ = false;
};

}  // namespace atlas::view
