#pragma once
// The thread that owns one device: opens it, runs the device's start-up sequence, reads until
// the device goes away, and reopens it with capped exponential backoff until it is back
// (issue 5, "Faults"). Subclasses (LaserReader, OdometryReader, SonarReader) supply Connect /
// ReadUntilGone / Disconnect and push their samples into their own SpscQueue, so the consumer
// never blocks on a device.
//
// Stop() is prompt: reads poll with a short timeout and the backoff sleep is interruptible.

#include <atomic>
#include <condition_variable>
#include <mutex>
#include <string>
#include <thread>

#include "core/common/time.h"
#include "drivers/device/driver_health.h"

namespace atlas {

struct ReconnectOptions {
  Duration initial_backoff = std::chrono::milliseconds(100);
  Duration max_backoff = std::chrono::seconds(2);
  int max_attempts = 0;  // consecutive failed attempts before kFailed; 0 = never give up
  // A connected device silent for this long is stalled (counted once per silence) ...
  Duration stall_timeout = std::chrono::milliseconds(1000);
  // ... and after this long it is reopened (a power-cycled device needs its start-up again).
  Duration reopen_after_silence = std::chrono::seconds(3);
  // > 0: run the reader thread SCHED_FIFO at this priority (1..99), so that a loaded machine
  // does not delay the arrival stamps. Needs CAP_SYS_NICE (or an rtprio limit); when it is
  // refused the thread runs normally and last_error says so.
  int realtime_priority = 0;
  std::string Validate() const;
};

// Backoff after `failures` consecutive failures (1, 2, ...): initial * 2^(failures-1), capped.
Duration BackoffDelay(const ReconnectOptions& options, int failures);

class DeviceReader {
 public:
  DeviceReader(std::string device, const ReconnectOptions& options);
  virtual ~DeviceReader();
  DeviceReader(const DeviceReader&) = delete;
  DeviceReader& operator=(const DeviceReader&) = delete;

  void Start();
  // Idempotent; joins the thread. Subclass destructors must call it.
  void Stop();
  bool running() const { return thread_.joinable(); }
  DriverHealth Health() const;

 protected:
  enum class SessionEnd { kStopped, kGone };

  // Opens the device and runs its start-up sequence. False with *error on failure.
  virtual bool Connect(std::string* error) = 0;
  // Reads until Stopping() or the device is gone (*error says why).
  virtual SessionEnd ReadUntilGone(std::string* error) = 0;
  virtual void Disconnect() = 0;
  // Queue drops, added to the health snapshot.
  virtual uint64_t QueueDrops() const = 0;

  bool Stopping() const { return stop_.load(std::memory_order_acquire); }
  // Interruptible sleep; false if stopped meanwhile.
  bool SleepFor(Duration d);
  // Silence bookkeeping for ReadUntilGone: call on every read with or without data. Returns
  // true when the silence has lasted reopen_after_silence (the session should end as gone).
  bool TrackSilence(bool got_data, Time now);

  DriverHealthRecorder health_;
  const ReconnectOptions reconnect_;

 private:
  void Loop();

  std::thread thread_;
  std::atomic<bool> stop_{false};
  std::mutex sleep_mutex_;
  std::condition_variable sleep_cv_;
  Time last_data_{};
  bool stalled_ = false;
};

}  // namespace atlas
