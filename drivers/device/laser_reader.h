#pragma once
// The SICK LMS 2xx reader thread (docs/devices.md, section 1). Start-up sequence:
//   1. open the line at 9600 8N1 raw and check the scanner answers a status request (0x31);
//      if nothing answers at 9600, try the other rates (the scanner may still be at a higher
//      rate after a host restart);
//   2. switch the scanner to the configured rate (0x20 0x48/0x40/0x41) and reopen the line at
//      that rate;
//   3. set the variant (0x3B: angular range, resolution);
//   4. start continuous output of all values (0x20 0x24).
// Then every 0xB0 telegram is decoded by the pure decoders of drivers/sick, stamped with the
// arrival time of the read that completed it, and pushed into a SpscQueue<LaserScan>.
// Bad CRCs, impossible LEN fields and bytes outside telegrams are counted (the stream decoder
// resynchronises on STX); a partial telegram followed by silence (truncation_gap) is counted as
// truncated and dropped. EOF/EIO/hang-up ends the session and the line is reopened with capped
// backoff, running the start-up sequence again.

#include <cstdint>
#include <functional>
#include <string>
#include <vector>

#include "core/common/sensor_types.h"
#include "drivers/device/device_reader.h"
#include "drivers/device/gap_resync.h"
#include "drivers/queue/spsc_queue.h"
#include "drivers/serial/serial_port.h"
#include "drivers/sick/lms_messages.h"
#include "drivers/sick/lms_telegram.h"

namespace atlas {

struct LaserReaderOptions {
  std::string device;                 // serial device or pty (symlink) path
  int baud = 500000;                  // operating rate: 9600, 19200, 38400 or 500000
  uint16_t angle_deg = 180;           // variant: 180 or 100
  uint16_t resolution_centideg = 50;  // variant: 100, 50 or 25
  Pose2 sensor_pose;                  // the scanner on the robot
  // The range unit the scanner is configured for (atlasd's laser.unit). Every telegram states
  // its unit and is decoded with it; a scan in another unit is still used, and the device
  // status reports the mismatch (a scanner configured differently than the file says).
  sick::Unit unit = sick::Unit::kMillimetre;
  // Returns at or beyond this many metres are no return and the scan's max_range is at most
  // this (atlasd's laser.max_range_m; LimitLaserRange). 0: the scanner's own maximum.
  float max_range = 0.0f;
  // Rates tried for the status check, in order; the first must be 9600 (power-up rate).
  std::vector<int> probe_rates = {9600, 500000, 38400, 19200};
  Duration reply_timeout = std::chrono::milliseconds(300);  // spec: replies within 60 ms
  // Silence inside a telegram that makes it truncated; well above the chunking of USB serial
  // adapters (FTDI latency timer: 16 ms) and a loaded machine's scheduling delays.
  Duration truncation_gap = std::chrono::milliseconds(100);
  size_t queue_capacity = 64;
  // Called by the reader thread right after each scan is queued, so that a consumer can block
  // until there is a scan instead of polling (atlasd's loop). Must be quick; may be empty.
  std::function<void()> on_scan;
  ReconnectOptions reconnect;
  std::string Validate() const;
};

class LaserReader final : public DeviceReader {
 public:
  explicit LaserReader(const LaserReaderOptions& options);  // options must be valid
  ~LaserReader() override;

  // Consumer side: never blocks.
  bool Pop(LaserScan* scan) { return queue_.Pop(scan); }
  SpscQueue<LaserScan>& queue() { return queue_; }
  // The rate at which the scanner last answered the status check (0 before).
  int found_baud() const { return found_baud_.load(std::memory_order_relaxed); }

 protected:
  bool Connect(std::string* error) override;
  SessionEnd ReadUntilGone(std::string* error) override;
  void Disconnect() override;
  uint64_t QueueDrops() const override { return queue_.Dropped(); }

 private:
  enum class Reply { kOk, kRejected, kTimeout, kGone };
  // Sends a host command and waits for the reply telegram `reply_code`; `accept` judges it.
  template <typename Accept>
  Reply Transact(const std::vector<uint8_t>& command, uint8_t reply_code, Accept&& accept,
                 std::string* error);
  void HandleTelegram(const sick::TelegramView& t, Time stamp);
  void SyncCounters();

  LaserReaderOptions options_;
  SerialPort port_;
  sick::StreamDecoder decoder_;
  GapResync<sick::StreamDecoder::kWindow> resync_;
  SpscQueue<LaserScan> queue_;
  LaserScan scan_;
  std::atomic<int> found_baud_{0};
};

}  // namespace atlas
