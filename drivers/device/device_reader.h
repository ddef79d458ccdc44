#pragma once
// The thread that owns one device: opens it, runs the device's start-up sequence, reads until
// the device goes away, and reopens it with capped exponential backoff until it is back.
// Subclasses (LaserReader, OdometryReader, SonarReader) supply Connect /
// ReadUntilGone / Disconnect and push their samples into their own SpscQueue, so the consumer
// never blocks on a device.
//
// Stop() is prompt: reads poll with a short timeout and the backoff sleep is interruptible.

#include <algorithm>
#include <atomic>
#include <condition_variable>
#include <cstdint>
#include <mutex>
#include <span>
#include <string>
#include <thread>

#include "core/common/time.h"
#include "drivers/device/driver_health.h"
#include "drivers/device/driver_log.h"
#include "drivers/device/gap_resync.h"
#include "drivers/serial/serial_port.h"

namespace atlas {

struct ReconnectOptions {
  Duration initial_backoff = std::chrono::milliseconds(100);
  Duration max_backoff = std::chrono::seconds(2);
  // Consecutive attempts that brought no data (failed opens, and sessions that ended before a
  // single message was decoded) at which a failed open gives up with kFailed; 0 = never.
  int max_attempts = 0;
  // A connected device silent for this long is stalled (counted once per silence) ...
  Duration stall_timeout = std::chrono::milliseconds(1000);
  // ... and after this long it is reopened (a power-cycled device needs its start-up again).
  Duration reopen_after_silence = std::chrono::seconds(3);
  // > 0: run the reader thread SCHED_FIFO at this priority (1..99), so that a loaded machine
  // does not delay the arrival stamps. Needs CAP_SYS_NICE (or an rtprio limit); when it is
  // refused the thread runs normally and last_error says so.
  int realtime_priority = 0;
  // Where the reader says each change of its state, once, with the reason (DriverLog); called
  // from the reader thread. May be empty (nothing is said; the health still has it all).
  DriverLogSink log;
  std::string Validate() const;
};

// Backoff after `failures` consecutive failures (1, 2, ...): initial * 2^(failures-1), capped.
// A failure is a failed open or a session that decoded no message (a device that opens and
// dies at once, e.g. SocketCAN on a down interface, must not be reopened at the initial rate
// forever); only a session that delivered data resets the count.
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
  // The sleep between reconnect attempts (SleepFor; tests record the delays).
  virtual bool BackoffSleep(Duration d) { return SleepFor(d); }
  // Silence bookkeeping for ReadUntilGone: call on every read with or without data. Returns
  // true when the silence has lasted reopen_after_silence (the session should end as gone).
  bool TrackSilence(bool got_data, Time now);
  // A condition of the device or its link (DriverLog::Condition), said once per change.
  void ReportCondition(LogPriority priority, std::string_view text) {
    Say(log_.Condition(priority, text));
  }

  // The session loop of a serial device (laser, sonar): polls `port`, feeds every byte to
  // `decoder` (and records it in `resync`), hands what the decoder finds to
  // on_event(event, arrival_time), abandons a partial frame after a silent `gap` (counted as
  // truncated; what refeeding the recorded bytes then finds keeps the arrival time of the last
  // bytes read, not the end of the gap), calls before_read() first on every turn (false: the device
  // is gone, *error set), keeps the counters in step with sync_counters(), and ends the session as
  // gone after reopen_after_silence without a byte (*error = who + ": silent ..." + what_next).
  template <typename Decoder, std::size_t N, typename OnEvent, typename BeforeRead,
            typename SyncCounters>
  SessionEnd ReadSerialUntilGone(SerialPort& port, Decoder& decoder, GapResync<N>& resync,
                                 Duration gap, OnEvent&& on_event, BeforeRead&& before_read,
                                 SyncCounters&& sync_counters, const std::string& who,
                                 const char* what_next, std::string* error) {
    uint8_t buf[4096];
    const int gap_ms = static_cast<int>(
        std::max<int64_t>(1, std::chrono::duration_cast<std::chrono::milliseconds>(gap).count()));
    Time last_arrival = Now();  // of the last bytes read
    while (!Stopping()) {
      if (!before_read()) return SessionEnd::kGone;
      const int timeout = decoder.buffered() > 0 ? gap_ms : 50;
      const SerialResult r = port.Read(buf, sizeof(buf), timeout);
      const Time now = Now();
      if (r.status == SerialIo::kGone || r.status == SerialIo::kError) {
        *error = r.error;
        sync_counters();
        return SessionEnd::kGone;
      }
      if (r.status == SerialIo::kTimeout && decoder.buffered() > 0) {
        health_.truncated.fetch_add(1, std::memory_order_relaxed);
        // What refeeding finds came with the bytes already read, a gap ago.
        resync.Resync(decoder, [&](const auto& event) { on_event(event, last_arrival); });
      }
      if (r.status == SerialIo::kData) {
        last_arrival = now;
        resync.Record(std::span<const uint8_t>(buf, r.n));
        decoder.FeedAll(std::span<const uint8_t>(buf, r.n),
                        [&](const auto& event) { on_event(event, now); });
      }
      sync_counters();
      if (TrackSilence(r.status == SerialIo::kData, now)) {
        *error = who + ": silent for " +
                 std::to_string(ToSeconds(reconnect_.reopen_after_silence)).substr(0, 4) + " s; " +
                 what_next;
        return SessionEnd::kGone;
      }
    }
    return SessionEnd::kStopped;
  }

  DriverHealthRecorder health_;
  const ReconnectOptions reconnect_;

 private:
  void Loop();
  void Say(const std::optional<DriverLogLine>& line) {
    if (line && reconnect_.log) reconnect_.log(*line);
  }

  std::thread thread_;
  std::atomic<bool> stop_{false};
  std::mutex sleep_mutex_;
  std::condition_variable sleep_cv_;
  Time last_data_{};
  bool stalled_ = false;
  DriverLog log_;  // reader thread only
  uint64_t session_start_messages_ = 0;
};

}  // namespace atlas
