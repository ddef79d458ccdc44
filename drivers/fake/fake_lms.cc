#include "drivers/fake/fake_lms.h"

#include "drivers/serial/serial_port.h"

namespace atlas::fake {

std::string FakeLmsOptions::Validate() const {
  if (!sick::BaudFromRate(power_up_baud))
    return "fake LMS: power_up_baud must be 9600, 19200, 38400 or 500000";
  return faults.Validate();
}

FakeLms::FakeLms(const FakeLmsOptions& options, std::shared_ptr<const Recording> recording,
                 std::shared_ptr<const PlaybackClock> clock)
    : FakeSerialDevice("fake LMS", options.link, options.faults, std::move(clock)),
      options_(options),
      recording_(std::move(recording)),
      sent_intact_(options.sent_record_capacity) {}

FakeLms::~FakeLms() { Stop(); }

void FakeLms::OnPowerUp() {
  baud_.store(options_.power_up_baud);
  streaming_.store(false);
  host_decoder_.Reset();
}

void FakeLms::Answer(const sick::HostCommand& c) {
  using K = sick::HostCommand::Kind;
  const uint8_t st = options_.status;
  switch (c.kind) {
    case K::kStatus:
      SendReply(sick::EncodeStatusReply(st));
      break;
    case K::kModeBaud:
      SendReply(sick::EncodeModeReply(true, st));
      baud_.store(sick::BaudRate(c.baud));  // the switch takes effect after the reply
      break;
    case K::kModeContinuous:
      SendReply(sick::EncodeModeReply(true, st));
      streaming_.store(true);
      break;
    case K::kModeOnRequest:
      SendReply(sick::EncodeModeReply(true, st));
      streaming_.store(false);
      break;
    case K::kModeInstallation:
      SendReply(sick::EncodeModeReply(true, st));
      break;
    case K::kVariant: {
      const bool ok =
          (c.angle_deg == 180 && (c.resolution_centideg == 100 || c.resolution_centideg == 50)) ||
          (c.angle_deg == 100 && (c.resolution_centideg == 100 || c.resolution_centideg == 50 ||
                                  c.resolution_centideg == 25));
      SendReply(sick::EncodeVariantReply(ok, c.angle_deg, c.resolution_centideg, st));
      break;
    }
    case K::kScanRequest: {
      const size_t i = next_scan_ > 0 ? next_scan_ - 1 : 0;
      if (auto t = sick::EncodeMeasuredValues(recording_->scans[i], options_.unit, st)) {
        t->insert(t->begin(), sick::kAck);
        SendReply(*t);
      }
      break;
    }
    case K::kUnknown:
      SendReply({sick::kNak});
      return;
  }
  commands_.fetch_add(1);
}

void FakeLms::OnHostBytes(std::span<const uint8_t> bytes, Time) {
  if (SlaveBaud() != baud_.load()) {
    // The host talks at another rate: the scanner would see only framing errors.
    wrong_rate_.fetch_add(1);
    host_decoder_.Reset();
    return;
  }
  host_decoder_.FeedAll(bytes, [&](const sick::StreamEvent& e) {
    if (e.kind != sick::StreamEventKind::kTelegram || e.telegram.is_reply()) return;
    Answer(sick::DecodeHostCommand(e.telegram));
  });
}

Time FakeLms::Tick(Time now) {
  const auto& scans = recording_->scans;
  while (next_scan_ < scans.size() && clock().WallAt(scans[next_scan_].stamp) <= now) {
    const size_t i = next_scan_++;
    if (!streaming_.load() || SlaveBaud() != baud_.load()) continue;
    auto t = sick::EncodeMeasuredValues(scans[i], options_.unit, options_.status);
    if (!t) continue;
    if (SendMessage(std::move(*t))) sent_intact_.Add(i);
  }
  if (next_scan_ >= scans.size()) {
    SetFinished();
    return now + std::chrono::milliseconds(20);
  }
  return clock().WallAt(scans[next_scan_].stamp);
}

bool AnswerLmsStartUp(PseudoTerminal& pty, Duration timeout, uint8_t status) {
  sick::StreamDecoder decoder;
  uint8_t buf[1024];
  const Time deadline = Now() + timeout;
  bool streaming = false;
  while (!streaming && Now() < deadline) {
    const long n = pty.Read(buf, sizeof(buf), 20);
    if (n <= 0) continue;
    decoder.FeedAll(
        std::span<const uint8_t>(buf, static_cast<size_t>(n)), [&](const sick::StreamEvent& e) {
          if (e.kind != sick::StreamEventKind::kTelegram || e.telegram.is_reply()) return;
          const sick::HostCommand c = sick::DecodeHostCommand(e.telegram);
          std::vector<uint8_t> reply;
          switch (c.kind) {
            case sick::HostCommand::Kind::kStatus:
              reply = sick::EncodeStatusReply(status);
              break;
            case sick::HostCommand::Kind::kVariant:
              reply = sick::EncodeVariantReply(true, c.angle_deg, c.resolution_centideg, status);
              break;
            case sick::HostCommand::Kind::kModeContinuous:
              streaming = true;
              [[fallthrough]];
            default:
              reply = sick::EncodeModeReply(true, status);
          }
          pty.WriteAll(reply.data(), reply.size());
        });
  }
  return streaming;
}

}  // namespace atlas::fake
