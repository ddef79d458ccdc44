#include "drivers/device/laser_reader.h"

#include <algorithm>
#include <cmath>
#include <cstdio>

namespace atlas {

std::string LaserReaderOptions::Validate() const {
  if (device.empty()) return "laser: device path is empty";
  if (!sick::BaudFromRate(baud))
    return "laser " + device + ": baud " + std::to_string(baud) +
           " is not an LMS rate (9600, 19200, 38400, 500000)";
  if (angle_deg != 180 && angle_deg != 100)
    return "laser " + device + ": angle_deg must be 180 or 100";
  if (resolution_centideg != 100 && resolution_centideg != 50 && resolution_centideg != 25)
    return "laser " + device + ": resolution_centideg must be 100, 50 or 25";
  if (angle_deg == 180 && resolution_centideg == 25)
    return "laser " + device + ": 0.25 deg resolution needs the 100 deg range";
  if (probe_rates.empty() || probe_rates.front() != 9600)
    return "laser " + device + ": probe_rates must start with 9600";
  for (int r : probe_rates)
    if (!sick::BaudFromRate(r)) return "laser " + device + ": bad probe rate " + std::to_string(r);
  if (reply_timeout <= Duration::zero() || truncation_gap <= Duration::zero())
    return "laser " + device + ": timeouts must be > 0";
  if (queue_capacity == 0) return "laser " + device + ": queue_capacity must be > 0";
  if (!(max_range >= 0.0f) || !std::isfinite(max_range))
    return "laser " + device + ": max_range must be >= 0 (0: the scanner's own)";
  return reconnect.Validate();
}

LaserReader::LaserReader(const LaserReaderOptions& options)
    : DeviceReader("laser " + options.device, options.reconnect),
      options_(options),
      queue_(options.queue_capacity) {}

LaserReader::~LaserReader() { Stop(); }

void LaserReader::Disconnect() { port_.Close(); }

void LaserReader::SyncCounters() {
  const sick::StreamCounters& c = decoder_.counters();
  health_.bytes.store(c.bytes_fed - resync_.double_counted(), std::memory_order_relaxed);
  health_.bad_crc.store(c.bad_crc, std::memory_order_relaxed);
  health_.bad_length.store(c.bad_length, std::memory_order_relaxed);
  health_.garbage_bytes.store(c.garbage_bytes - resync_.double_counted(),
                              std::memory_order_relaxed);
}

template <typename Accept>
LaserReader::Reply LaserReader::Transact(const std::vector<uint8_t>& command, uint8_t reply_code,
                                         Accept&& accept, std::string* error) {
  SerialResult w = port_.WriteAll(command.data(), command.size(), 500);
  if (w.status != SerialIo::kData) {
    *error = w.error;
    return w.status == SerialIo::kGone ? Reply::kGone : Reply::kTimeout;
  }
  const Time deadline = Now() + options_.reply_timeout;
  uint8_t buf[1024];
  Reply result = Reply::kTimeout;
  bool done = false;
  while (!done && !Stopping()) {
    const auto left = std::chrono::duration_cast<std::chrono::milliseconds>(deadline - Now());
    if (left.count() <= 0) break;
    SerialResult r = port_.Read(buf, sizeof(buf), static_cast<int>(left.count()));
    const Time arrival = Now();  // the stamp of every scan in these bytes, as in a session
    if (r.status == SerialIo::kGone || r.status == SerialIo::kError) {
      *error = r.error;
      return Reply::kGone;
    }
    if (r.status != SerialIo::kData) continue;
    resync_.Record(std::span<const uint8_t>(buf, r.n));
    decoder_.FeedAll(std::span<const uint8_t>(buf, r.n), [&](const sick::StreamEvent& e) {
      if (done) return;
      if (e.kind == sick::StreamEventKind::kNak) {
        result = Reply::kRejected;
        done = true;
      } else if (e.kind == sick::StreamEventKind::kTelegram) {
        if (e.telegram.command == sick::kReplyValues && reply_code != sick::kReplyValues) {
          HandleTelegram(e.telegram, arrival);  // a scan already streaming: keep it
        } else if (e.telegram.command == reply_code) {
          result = accept(e.telegram) ? Reply::kOk : Reply::kRejected;
          done = true;
        } else if (e.telegram.command == sick::kReplyIncorrectCommand) {
          result = Reply::kRejected;
          done = true;
        }
      }
    });
  }
  SyncCounters();
  if (result == Reply::kTimeout) *error = "no reply";
  if (result == Reply::kRejected) *error = "command rejected";
  return result;
}

bool LaserReader::Connect(std::string* error) {
  const std::string who = "laser " + options_.device;
  decoder_.Reset();
  // 1. Find the scanner: 9600 first, then the other rates.
  int found = 0;
  std::string last;
  for (int rate : options_.probe_rates) {
    if (Stopping()) return false;
    SerialOptions so{options_.device, rate, true};
    if (!port_.Open(so, &last)) {
      *error = last;
      return false;  // the line itself is missing/busy: no point in other rates
    }
    std::string why;
    std::optional<sick::StatusReply> status;
    const Reply r = Transact(
        sick::EncodeStatusRequest(), sick::kReplyStatus,
        [&](const sick::TelegramView& t) {
          return (status = sick::DecodeStatusReply(t)).has_value();
        },
        &why);
    if (r == Reply::kGone) {
      *error = why;
      return false;
    }
    if (r == Reply::kOk) {
      found = rate;
      health_.SetDeviceStatus("scanner " + status->software_version + " status 0x" + [&] {
        char b[8];
        std::snprintf(b, sizeof(b), "%02X", status->status.raw);
        return std::string(b);
      }());
      break;
    }
  }
  if (found == 0) {
    std::string rates;
    for (int r : options_.probe_rates) rates += (rates.empty() ? "" : ", ") + std::to_string(r);
    *error = who + ": no answer to the status request at " + rates +
             " baud: is the scanner powered and connected?";
    return false;
  }
  found_baud_.store(found, std::memory_order_relaxed);
  // 2. Switch to the configured rate and reopen the line at it.
  std::string why;
  if (found != options_.baud) {
    std::optional<sick::ModeReply> mode;
    const Reply r = Transact(
        sick::EncodeModeBaud(*sick::BaudFromRate(options_.baud)), sick::kReplyMode,
        [&](const sick::TelegramView& t) {
          mode = sick::DecodeModeReply(t);
          return mode && mode->success;
        },
        &why);
    if (r != Reply::kOk) {
      *error = who + ": switching to " + std::to_string(options_.baud) + " baud failed: " + why;
      return false;
    }
    if (!port_.Reopen(options_.baud, &why)) {
      *error = why;
      return false;
    }
    decoder_.Reset();
  }
  // 3. Variant.
  const Reply rv = Transact(
      sick::EncodeVariantRequest(options_.angle_deg, options_.resolution_centideg),
      sick::kReplyVariant,
      [&](const sick::TelegramView& t) {
        auto v = sick::DecodeVariantReply(t);
        return v && v->accepted;
      },
      &why);
  if (rv != Reply::kOk) {
    *error = who + ": variant " + std::to_string(options_.angle_deg) + " deg / " +
             std::to_string(options_.resolution_centideg) + " centideg: " + why;
    return false;
  }
  // 4. Continuous output.
  const Reply rc = Transact(
      sick::EncodeModeContinuous(), sick::kReplyMode,
      [&](const sick::TelegramView& t) {
        auto m = sick::DecodeModeReply(t);
        return m && m->success;
      },
      &why);
  if (rc != Reply::kOk) {
    *error = who + ": starting continuous output: " + why;
    return false;
  }
  return true;
}

void LaserReader::HandleTelegram(const sick::TelegramView& t, Time stamp) {
  if (t.command != sick::kReplyValues) return;  // late replies to start-up commands
  sick::ScanInfo info;
  sick::ScanOptions so;
  so.sensor_pose = options_.sensor_pose;
  if (sick::DecodeMeasuredValues(t, stamp, so, &scan_, &info) != sick::ScanDecode::kOk) {
    health_.bad_messages.fetch_add(1, std::memory_order_relaxed);
    return;
  }
  health_.CountMessage(stamp);
  if (options_.max_range > 0.0f) LimitLaserRange(&scan_, options_.max_range);
  if (info.unit != options_.unit) {
    const char* mismatch = info.unit == sick::Unit::kMillimetre ? "scans in mm, laser.unit says cm"
                                                                : "scans in cm, laser.unit says mm";
    health_.SetDeviceStatus(mismatch);
    ReportCondition(LogPriority::kWarning, mismatch);
  } else if (info.status.level() != sick::StatusLevel::kOk || info.status.pollution()) {
    char b[64];
    std::snprintf(b, sizeof(b), "scanner status 0x%02X%s", info.status.raw,
                  info.status.pollution() ? " (window dirty)" : "");
    health_.SetDeviceStatus(b);
    ReportCondition(LogPriority::kWarning, b);
  }
  queue_.Push(std::move(scan_));
  if (options_.on_scan) options_.on_scan();
  health_.samples.fetch_add(1, std::memory_order_relaxed);
  scan_ = LaserScan{};
}

DeviceReader::SessionEnd LaserReader::ReadUntilGone(std::string* error) {
  return ReadSerialUntilGone(
      port_, decoder_, resync_, options_.truncation_gap,
      [&](const sick::StreamEvent& e, Time arrival) {
        if (e.kind == sick::StreamEventKind::kTelegram) HandleTelegram(e.telegram, arrival);
      },
      [] { return true; }, [&] { SyncCounters(); }, "laser " + options_.device,
      "restarting the scanner", error);
}

}  // namespace atlas
