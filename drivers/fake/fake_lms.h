#pragma once
// A fake SICK LMS 2xx on a pseudo-terminal (docs/devices.md, section 1). It powers up
// at 9600 baud with output off and follows the protocol as the real scanner does: it answers
// the status request (0x31 -> B1), the mode commands (0x20 -> A0: baud switch, continuous
// output, values on request, installation mode), the variant (0x3B -> BB) and single-scan
// requests (0x30 -> B0), each after an ACK, and NAKs what it does not understand. A pty has no
// line rate, but the rate the host set on the slave is visible: the fake ignores the host
// while the host's rate is not the scanner's current rate (as a real scanner would see only
// garbage), so the driver's rate probing and baud switch are exercised for real.
// In continuous mode it sends the recording's scans as 0xB0 telegrams at their log times.

#include <cstdint>
#include <memory>

#include "drivers/fake/fake_serial_device.h"
#include "drivers/fake/sent_record.h"
#include "drivers/sick/lms_messages.h"
#include "drivers/sick/lms_telegram.h"

namespace atlas::fake {

struct FakeLmsOptions {
  std::string link;          // symlink to (re)create at the pty's slave; empty: none
  int power_up_baud = 9600;  // the scanner's rate after (re)power
  sick::Unit unit = sick::Unit::kCentimetre;
  uint8_t status = 0x10;  // STATUS byte of every reply
  // sent_intact() keeps the last N
  size_t sent_record_capacity = kDefaultSentRecordCapacity;
  FaultOptions faults;
  std::string Validate() const;
};

class FakeLms final : public FakeSerialDevice {
 public:
  FakeLms(const FakeLmsOptions& options, std::shared_ptr<const Recording> recording,
          std::shared_ptr<const PlaybackClock> clock);
  ~FakeLms() override;

  int baud() const { return baud_.load(); }
  bool streaming() const { return streaming_.load(); }
  // Indices (into recording->scans) of the scans sent intact, in order: the last
  // sent_record_capacity of them, and the count of all.
  const SentRecord<size_t>& sent_intact() const { return sent_intact_; }
  uint64_t commands_answered() const { return commands_.load(); }
  uint64_t commands_ignored_wrong_rate() const { return wrong_rate_.load(); }

 protected:
  void OnPowerUp() override;
  void OnHostBytes(std::span<const uint8_t> bytes, Time now) override;
  Time Tick(Time now) override;

 private:
  void Answer(const sick::HostCommand& c);

  FakeLmsOptions options_;
  std::shared_ptr<const Recording> recording_;
  sick::StreamDecoder host_decoder_;
  std::atomic<int> baud_{9600};
  std::atomic<bool> streaming_{false};
  std::atomic<uint64_t> commands_{0};
  std::atomic<uint64_t> wrong_rate_{0};
  size_t next_scan_ = 0;
  SentRecord<size_t> sent_intact_;
};

// For benchmarks that write the 0xB0 telegrams themselves on a pseudo-terminal they own: answers
// the host's start-up sequence as the scanner does (status, mode and variant requests, each
// acknowledged; at whatever rate the host set, the baud switch included) until the host asks for
// continuous output (true) or `timeout` passes (false).
bool AnswerLmsStartUp(PseudoTerminal& pty, Duration timeout, uint8_t status = 0x10);

}  // namespace atlas::fake
