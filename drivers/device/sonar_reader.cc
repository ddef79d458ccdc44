#include "drivers/device/sonar_reader.h"

#include <algorithm>

namespace atlas {

std::string SonarReaderOptions::Validate() const {
  if (device.empty()) return "sonar: device path is empty";
  if (probe_rates.empty()) return "sonar " + device + ": probe_rates is empty";
  for (int r : probe_rates)
    if (!IsSupportedBaud(r)) return "sonar " + device + ": bad probe rate " + std::to_string(r);
  if (std::string e = sonar.Validate(); !e.empty()) return "sonar " + device + ": " + e;
  if (reply_timeout <= Duration::zero() || truncation_gap <= Duration::zero())
    return "sonar " + device + ": timeouts must be > 0";
  // A PULSE goes out on the first read turn at or after pulse_period; a turn waits at most
  // max(truncation_gap, 50 ms) (DeviceReader::ReadSerialUntilGone).
  const Duration turn = std::max<Duration>(truncation_gap, std::chrono::milliseconds(50));
  if (pulse_period <= Duration::zero() || pulse_period + turn >= std::chrono::seconds(1))
    return "sonar " + device +
           ": pulse_period plus one read turn (max(truncation_gap, 50 ms)) must stay under 1 s "
           "(the controller's watchdog wants a PULSE at least once a second)";
  if (queue_capacity == 0) return "sonar " + device + ": queue_capacity must be > 0";
  return reconnect.Validate();
}

SonarReader::SonarReader(const SonarReaderOptions& options)
    : DeviceReader("sonar " + options.device, options.reconnect),
      options_(options),
      queue_(options.queue_capacity) {}

SonarReader::~SonarReader() { Stop(); }

void SonarReader::Disconnect() { port_.Close(); }

void SonarReader::SyncCounters() {
  const p2os::StreamCounters& c = decoder_.counters();
  health_.bytes.store(c.bytes_fed - resync_.double_counted(), std::memory_order_relaxed);
  health_.bad_crc.store(c.bad_checksum, std::memory_order_relaxed);
  health_.bad_length.store(c.bad_count, std::memory_order_relaxed);
  health_.garbage_bytes.store(c.garbage_bytes - resync_.double_counted(),
                              std::memory_order_relaxed);
}

bool SonarReader::Send(const std::vector<uint8_t>& packet, std::string* error) {
  SerialResult w = port_.WriteAll(packet.data(), packet.size(), 500);
  if (w.status != SerialIo::kData) {
    *error = w.error;
    return false;
  }
  return true;
}

template <typename Accept>
bool SonarReader::Exchange(const std::vector<uint8_t>& packet, Accept&& accept,
                           std::string* error) {
  if (!Send(packet, error)) return false;
  const Time deadline = Now() + options_.reply_timeout;
  uint8_t buf[512];
  bool done = false;
  while (!done && !Stopping()) {
    const auto left = std::chrono::duration_cast<std::chrono::milliseconds>(deadline - Now());
    if (left.count() <= 0) break;
    SerialResult r = port_.Read(buf, sizeof(buf), static_cast<int>(left.count()));
    if (r.status == SerialIo::kGone || r.status == SerialIo::kError) {
      *error = r.error;
      return false;
    }
    if (r.status != SerialIo::kData) continue;
    resync_.Record(std::span<const uint8_t>(buf, r.n));
    decoder_.FeedAll(std::span<const uint8_t>(buf, r.n), [&](const p2os::PacketView& p) {
      if (!done && accept(p)) done = true;
    });
  }
  SyncCounters();
  if (!done) *error = "no reply";
  return done;
}

bool SonarReader::Connect(std::string* error) {
  const std::string who = "sonar " + options_.device;
  decoder_.Reset();
  bool synced = false;
  for (int rate : options_.probe_rates) {
    if (Stopping()) return false;
    if (!port_.Open({options_.device, rate, true}, error)) return false;
    std::string why;
    bool saw_sip = false;
    auto sync0_echo = [&](const p2os::PacketView& p) {
      if (p2os::IsStandardSipType(p.payload[0])) saw_sip = true;
      return p2os::SyncEcho(p) == 0;
    };
    if (Exchange(p2os::EncodeSync(0), sync0_echo, &why)) {
      synced = true;
      break;
    }
    if (saw_sip && port_.is_open()) {
      // Still open from an earlier session (SYNC0 reads as PULSE then): close it, retry.
      if (Send(p2os::EncodeCommand(p2os::kCmdClose), &why) &&
          SleepFor(std::chrono::milliseconds(100))) {
        decoder_.Reset();
        if (Exchange(p2os::EncodeSync(0), sync0_echo, &why)) {
          synced = true;
          break;
        }
      }
    }
    if (!port_.is_open()) {
      *error = why;
      return false;
    }
  }
  if (!synced) {
    std::string rates;
    for (int r : options_.probe_rates) rates += (rates.empty() ? "" : ", ") + std::to_string(r);
    *error = who + ": no SYNC0 echo at " + rates + " baud: is the controller on and connected?";
    return false;
  }
  std::string why;
  if (!Exchange(
          p2os::EncodeSync(1), [](const p2os::PacketView& p) { return p2os::SyncEcho(p) == 1; },
          &why)) {
    *error = who + ": SYNC1: " + why;
    return false;
  }
  std::optional<p2os::RobotIdentity> id;
  if (!Exchange(
          p2os::EncodeSync(2),
          [&](const p2os::PacketView& p) { return (id = p2os::DecodeSync2Reply(p)).has_value(); },
          &why)) {
    *error = who + ": SYNC2: " + why;
    return false;
  }
  health_.SetDeviceStatus("robot " + id->name + " (" + id->robot_class + " " + id->subclass + ")");
  if (!Send(p2os::EncodeOpen(), &why) || !Send(p2os::EncodeSonarOn(), &why)) {
    *error = who + ": OPEN / sonar on: " + why;
    return false;
  }
  last_pulse_ = Now();
  return true;
}

void SonarReader::HandlePacket(const p2os::PacketView& p, Time stamp) {
  if (!p2os::IsStandardSipType(p.payload[0])) return;  // SYNC echoes, other SIP types
  if (p2os::DecodeStandardSip(p, &sip_) != p2os::SipDecode::kOk) {
    health_.bad_messages.fetch_add(1, std::memory_order_relaxed);
    return;
  }
  health_.CountMessage(stamp);
  p2os::ToSonarReading(sip_, stamp, options_.sonar, &reading_);
  if (reading_.returns.empty()) return;
  queue_.Push(std::move(reading_));
  if (options_.on_reading) options_.on_reading();
  health_.samples.fetch_add(1, std::memory_order_relaxed);
  reading_ = SonarReading{};
}

DeviceReader::SessionEnd SonarReader::ReadUntilGone(std::string* error) {
  auto pulse_if_due = [&] {
    const Time now = Now();
    if (now - last_pulse_ < options_.pulse_period) return true;
    if (!Send(p2os::EncodePulse(), error)) return false;
    pulses_.fetch_add(1, std::memory_order_relaxed);
    last_pulse_ = now;
    return true;
  };
  return ReadSerialUntilGone(
      port_, decoder_, resync_, options_.truncation_gap,
      [&](const p2os::PacketView& p, Time arrival) { HandlePacket(p, arrival); }, pulse_if_due,
      [&] { SyncCounters(); }, "sonar " + options_.device, "handshaking again", error);
}

}  // namespace atlas
