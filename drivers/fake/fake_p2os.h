#pragma once
// A fake Pioneer P2OS controller on a pseudo-terminal (docs/devices.md, section 3): the
// SYNC0/SYNC1/SYNC2 handshake (echoes; SYNC2 names the robot), OPEN, sonar on/off, PULSE and
// CLOSE; once open it sends a standard SIP every sip_period of log time, carrying the sonar
// returns of the ring synthesised from the recording's laser scan at that time (each
// transducer sees the nearest laser return inside its cone; the laser stands in for the
// sonar, so that a CARMEN log without sonar still drives the sonar path). Without a PULSE
// (or any command) for `watchdog` of wall time it closes the connection, as the controller
// does. Like the fake LMS it answers only at its line rate.

#include <memory>
#include <vector>

#include "drivers/fake/fake_serial_device.h"
#include "drivers/fake/sent_record.h"
#include "drivers/p2os/p2os_messages.h"
#include "drivers/p2os/p2os_packet.h"

namespace atlas::fake {

struct FakeP2osOptions {
  std::string link;
  int baud = 9600;
  p2os::SonarOptions sonar;  // ring geometry and range factor
  p2os::RobotIdentity identity{"atlas-fake", "Pioneer", "p3dx"};
  double sip_period_s = 0.1;  // log time between SIPs
  Duration watchdog = std::chrono::seconds(2);
  // sent_intact() and pulse_times() keep the last N each
  size_t sent_record_capacity = kDefaultSentRecordCapacity;
  FaultOptions faults;
  std::string Validate() const;
};

// The ring's view of a laser scan taken at the robot's centre: for every transducer, the
// nearest return among the beams within half the beam width of its heading (kNoReturn when
// none, or beyond max_range). Pure.
SonarReading SonarFromScan(const LaserScan& scan, const std::vector<SonarTransducer>& ring);

class FakeP2os final : public FakeSerialDevice {
 public:
  FakeP2os(const FakeP2osOptions& options, std::shared_ptr<const Recording> recording,
           std::shared_ptr<const PlaybackClock> clock);
  ~FakeP2os() override;

  bool is_open() const { return state_.load() == State::kOpen; }
  uint64_t watchdog_closes() const { return watchdog_closes_.load(); }
  // The readings carried by the SIPs sent intact (with at least one return), in order; and
  // when each PULSE arrived (the fake's clock), in order. Each: the last sent_record_capacity,
  // and the count of all (pulse_times().total() is the number of PULSEs).
  const SentRecord<SonarReading>& sent_intact() const { return sent_intact_; }
  const SentRecord<Time>& pulse_times() const { return pulse_times_; }

 protected:
  void OnPowerUp() override;
  void OnHostBytes(std::span<const uint8_t> bytes, Time now) override;
  Time Tick(Time now) override;

 private:
  enum class State { kWaitSync0, kWaitSync1, kWaitSync2, kReady, kOpen };

  FakeP2osOptions options_;
  std::shared_ptr<const Recording> recording_;
  p2os::StreamDecoder host_decoder_;
  std::atomic<State> state_{State::kWaitSync0};
  bool sonar_on_ = false;
  Time last_command_{};
  Time next_sip_log_{};
  uint16_t timer_ = 0;
  std::atomic<uint64_t> watchdog_closes_{0};
  SentRecord<SonarReading> sent_intact_;
  SentRecord<Time> pulse_times_;
};

}  // namespace atlas::fake
