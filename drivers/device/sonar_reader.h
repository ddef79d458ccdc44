#pragma once
// The P2OS sonar reader thread (docs/devices.md, section 3). Start-up: open the line at
// 9600 8N1 raw (or the next probe rate if no SYNC0 echo comes; SIPs instead of an echo mean
// the controller is still open from an earlier session: CLOSE, then SYNC0 again), the
// SYNC0/SYNC1/SYNC2 handshake (each echoed; SYNC2's echo names the robot), OPEN, sonar on (command
// 28, 1); then a PULSE about every pulse_period (the controller closes the connection when
// none comes for a second).
// Standard SIPs are decoded by drivers/p2os, their sonar returns converted with the configured
// range factor and ring geometry, and each SIP with returns is pushed as a SonarReading stamped at
// arrival. Bad checksums, bad counts, garbage and truncated packets are counted; EOF/EIO ends the
// session and the line is reopened with capped backoff (handshake again).

#include <functional>
#include <string>
#include <vector>

#include "core/common/sensor_types.h"
#include "drivers/device/device_reader.h"
#include "drivers/device/gap_resync.h"
#include "drivers/p2os/p2os_messages.h"
#include "drivers/p2os/p2os_packet.h"
#include "drivers/queue/spsc_queue.h"
#include "drivers/serial/serial_port.h"

namespace atlas {

struct SonarReaderOptions {
  std::string device;
  std::vector<int> probe_rates = {9600, 19200, 38400, 57600, 115200};
  p2os::SonarOptions sonar;
  // The controller wants a PULSE at least once a second. It is sent on the first read turn at
  // or after pulse_period, so the interval is up to one turn longer (a turn waits at most
  // max(truncation_gap, 50 ms)); Validate() keeps pulse_period plus a turn under 1 s.
  Duration pulse_period = std::chrono::milliseconds(500);
  Duration reply_timeout = std::chrono::milliseconds(300);
  Duration truncation_gap = std::chrono::milliseconds(100);  // see LaserReaderOptions
  size_t queue_capacity = 64;
  // Called by the reader thread right after each reading is queued (as LaserReaderOptions::
  // on_scan), so that a consumer can block until there is one (atlasd's loop when the local
  // maps use the sonar). Must be quick; may be empty.
  std::function<void()> on_reading;
  ReconnectOptions reconnect;
  std::string Validate() const;
};

class SonarReader final : public DeviceReader {
 public:
  explicit SonarReader(const SonarReaderOptions& options);  // options must be valid
  ~SonarReader() override;

  bool Pop(SonarReading* reading) { return queue_.Pop(reading); }
  SpscQueue<SonarReading>& queue() { return queue_; }
  uint64_t pulses_sent() const { return pulses_.load(std::memory_order_relaxed); }

 protected:
  bool Connect(std::string* error) override;
  SessionEnd ReadUntilGone(std::string* error) override;
  void Disconnect() override;
  uint64_t QueueDrops() const override { return queue_.Dropped(); }

 private:
  // Sends `packet` and waits for a controller packet that `accept` takes.
  template <typename Accept>
  bool Exchange(const std::vector<uint8_t>& packet, Accept&& accept, std::string* error);
  bool Send(const std::vector<uint8_t>& packet, std::string* error);
  void HandlePacket(const p2os::PacketView& p, Time stamp);
  void SyncCounters();

  SonarReaderOptions options_;
  SerialPort port_;
  p2os::StreamDecoder decoder_;
  GapResync<p2os::StreamDecoder::kWindow> resync_;
  SpscQueue<SonarReading> queue_;
  p2os::StandardSip sip_;
  SonarReading reading_;
  Time last_pulse_{};
  std::atomic<uint64_t> pulses_{0};
};

}  // namespace atlas
