#include "drivers/sick/lms_messages.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <numbers>

namespace atlas::sick {
namespace {

std::vector<uint8_t> HostTelegram(uint8_t command, std::span<const uint8_t> data) {
  return EncodeTelegram(kHostAddress, command, data);
}

std::vector<uint8_t> AckedReply(uint8_t command, std::span<const uint8_t> data, uint8_t status) {
  std::vector<uint8_t> out{kAck};
  const std::vector<uint8_t> t = EncodeTelegram(kScannerAddress, command, data, status);
  out.insert(out.end(), t.begin(), t.end());
  return out;
}

uint16_t U16(std::span<const uint8_t> b, std::size_t at) {
  return static_cast<uint16_t>(b[at] | (b[at + 1] << 8));
}

void PutU16(std::vector<uint8_t>* out, uint16_t v) {
  out->push_back(static_cast<uint8_t>(v & 0xFF));
  out->push_back(static_cast<uint8_t>(v >> 8));
}

constexpr std::size_t kStatusBlockSize = 152;
constexpr std::size_t kVersionSize = 7;
constexpr std::size_t kMaxEncodableBeams = (kMaxLen - 4) / 2;  // B0, count word, STATUS

}  // namespace

int BaudRate(Baud b) {
  switch (b) {
    case Baud::k9600:
      return 9600;
    case Baud::k19200:
      return 19200;
    case Baud::k38400:
      return 38400;
    case Baud::k500000:
      return 500000;
  }
  return 0;
}

std::optional<Baud> BaudFromRate(int bits_per_second) {
  for (Baud b : {Baud::k9600, Baud::k19200, Baud::k38400, Baud::k500000}) {
    if (BaudRate(b) == bits_per_second) return b;
  }
  return std::nullopt;
}

double UnitMetres(Unit u) { return u == Unit::kMillimetre ? 0.001 : 0.01; }

std::vector<uint8_t> EncodeStatusRequest() { return HostTelegram(kCmdStatus, {}); }

std::vector<uint8_t> EncodeModeBaud(Baud baud) {
  const std::array<uint8_t, 1> d{static_cast<uint8_t>(baud)};
  return HostTelegram(kCmdMode, d);
}

std::vector<uint8_t> EncodeModeContinuous() {
  const std::array<uint8_t, 1> d{kModeContinuous};
  return HostTelegram(kCmdMode, d);
}

std::vector<uint8_t> EncodeModeOnRequest() {
  const std::array<uint8_t, 1> d{kModeOnRequest};
  return HostTelegram(kCmdMode, d);
}

std::vector<uint8_t> EncodeModeInstallation() {
  std::vector<uint8_t> d{kModeInstallation};
  d.insert(d.end(), kInstallationPassword.begin(), kInstallationPassword.end());
  return HostTelegram(kCmdMode, d);
}

std::vector<uint8_t> EncodeVariantRequest(uint16_t angle_deg, uint16_t resolution_centideg) {
  std::vector<uint8_t> d;
  PutU16(&d, angle_deg);
  PutU16(&d, resolution_centideg);
  return HostTelegram(kCmdVariant, d);
}

std::vector<uint8_t> EncodeScanRequest() {
  const std::array<uint8_t, 1> d{0x01};
  return HostTelegram(kCmdRequestValues, d);
}

HostCommand DecodeHostCommand(const TelegramView& t) {
  HostCommand c;
  if (t.is_reply()) return c;
  const auto& d = t.data;
  switch (t.command) {
    case kCmdStatus:
      if (d.empty()) c.kind = HostCommand::Kind::kStatus;
      break;
    case kCmdRequestValues:
      if (d.size() == 1 && d[0] == 0x01) c.kind = HostCommand::Kind::kScanRequest;
      break;
    case kCmdVariant:
      if (d.size() == 4) {
        c.kind = HostCommand::Kind::kVariant;
        c.angle_deg = U16(d, 0);
        c.resolution_centideg = U16(d, 2);
      }
      break;
    case kCmdMode:
      if (d.size() == 1) {
        if (d[0] == kModeContinuous) {
          c.kind = HostCommand::Kind::kModeContinuous;
        } else if (d[0] == kModeOnRequest) {
          c.kind = HostCommand::Kind::kModeOnRequest;
        } else if (BaudRate(static_cast<Baud>(d[0])) != 0) {
          c.kind = HostCommand::Kind::kModeBaud;
          c.baud = static_cast<Baud>(d[0]);
        }
      } else if (d.size() == 1 + kInstallationPassword.size() && d[0] == kModeInstallation &&
                 std::equal(kInstallationPassword.begin(), kInstallationPassword.end(),
                            d.begin() + 1)) {
        c.kind = HostCommand::Kind::kModeInstallation;
      }
      break;
    default:
      break;
  }
  return c;
}

StatusLevel ScannerStatus::level() const {
  switch (raw & 0x0F) {
    case 0:
      return StatusLevel::kOk;
    case 3:
      return StatusLevel::kError;
    case 4:
      return StatusLevel::kFatal;
    default:
      return StatusLevel::kOther;
  }
}

std::vector<uint8_t> EncodeModeReply(bool success, uint8_t status) {
  const std::array<uint8_t, 1> d{static_cast<uint8_t>(success ? 0x00 : 0x01)};
  return AckedReply(kReplyMode, d, status);
}

std::vector<uint8_t> EncodeStatusReply(uint8_t status, std::string_view software_version) {
  std::vector<uint8_t> d(kStatusBlockSize, 0);
  for (std::size_t i = 0; i < kVersionSize && i < software_version.size(); ++i) {
    d[i] = static_cast<uint8_t>(software_version[i]);
  }
  return AckedReply(kReplyStatus, d, status);
}

std::vector<uint8_t> EncodeVariantReply(bool accepted, uint16_t angle_deg,
                                        uint16_t resolution_centideg, uint8_t status) {
  std::vector<uint8_t> d{static_cast<uint8_t>(accepted ? 0x01 : 0x00)};
  PutU16(&d, angle_deg);
  PutU16(&d, resolution_centideg);
  return AckedReply(kReplyVariant, d, status);
}

std::vector<uint8_t> EncodeIncorrectCommandReply(uint8_t status) {
  return AckedReply(kReplyIncorrectCommand, {}, status);
}

std::optional<ModeReply> DecodeModeReply(const TelegramView& t) {
  if (t.command != kReplyMode || !t.status || t.data.size() != 1) return std::nullopt;
  return ModeReply{t.data[0] == 0x00, ScannerStatus{*t.status}};
}

std::optional<StatusReply> DecodeStatusReply(const TelegramView& t) {
  if (t.command != kReplyStatus || !t.status || t.data.size() < kVersionSize) return std::nullopt;
  StatusReply r;
  r.software_version.assign(t.data.begin(), t.data.begin() + kVersionSize);
  while (!r.software_version.empty() &&
         (r.software_version.back() == ' ' || r.software_version.back() == '\0')) {
    r.software_version.pop_back();
  }
  r.status.raw = *t.status;
  return r;
}

std::optional<VariantReply> DecodeVariantReply(const TelegramView& t) {
  if (t.command != kReplyVariant || !t.status || t.data.size() != 5) return std::nullopt;
  VariantReply r;
  r.accepted = t.data[0] == 0x01;
  r.angle_deg = U16(t.data, 1);
  r.resolution_centideg = U16(t.data, 3);
  r.status.raw = *t.status;
  return r;
}

ScanDecode DecodeMeasuredValues(const TelegramView& t, Time stamp, const ScanOptions& options,
                                LaserScan* scan, ScanInfo* info) {
  if (t.command != kReplyValues || !t.status || t.data.size() < 2) {
    return ScanDecode::kNotMeasuredValues;
  }
  const uint16_t count_word = U16(t.data, 0);
  const int n = count_word & 0x03FF;
  if (t.data.size() != 2 + 2 * static_cast<std::size_t>(n)) return ScanDecode::kLengthMismatch;
  const int unit_bits = count_word >> 14;
  if (unit_bits > 1) return ScanDecode::kBadUnit;
  double fov_deg = 0.0;
  if (n == 181 || n == 361) {
    fov_deg = 180.0;
  } else if (n == 101 || n == 201 || n == 401) {
    fov_deg = 100.0;
  } else {
    return ScanDecode::kUnsupportedCount;
  }
  const Unit unit = static_cast<Unit>(unit_bits);
  const double metres = UnitMetres(unit);
  constexpr double kDeg = std::numbers::pi / 180.0;
  scan->stamp = stamp;
  scan->angle_min = static_cast<float>(-0.5 * fov_deg * kDeg);
  scan->angle_increment = static_cast<float>(fov_deg / (n - 1) * kDeg);
  scan->max_range = static_cast<float>((kFirstNoReturnCode - 1) * metres);
  scan->sensor_pose = options.sensor_pose;
  scan->ranges.resize(static_cast<std::size_t>(n));
  int no_return = 0;
  for (int i = 0; i < n; ++i) {
    const uint16_t v = U16(t.data, 2 + 2 * static_cast<std::size_t>(i)) & kRangeMask;
    if (v >= kFirstNoReturnCode) {
      scan->ranges[static_cast<std::size_t>(i)] = kNoReturn;
      ++no_return;
    } else {
      scan->ranges[static_cast<std::size_t>(i)] = static_cast<float>(v * metres);
    }
  }
  if (info != nullptr) {
    info->count = n;
    info->partial_scan = (count_word >> 11) & 0x3;
    info->scan_type = ((count_word >> 13) & 0x1) != 0;
    info->unit = unit;
    info->status.raw = *t.status;
    info->no_return_beams = no_return;
  }
  return ScanDecode::kOk;
}

std::optional<std::vector<uint8_t>> EncodeMeasuredValues(const LaserScan& scan, Unit unit,
                                                         uint8_t status) {
  const std::size_t n = scan.ranges.size();
  if (n == 0 || n > kMaxEncodableBeams) return std::nullopt;
  const double metres = UnitMetres(unit);
  std::vector<uint8_t> d;
  d.reserve(2 + 2 * n);
  PutU16(&d, static_cast<uint16_t>(n | (static_cast<std::size_t>(unit) << 14)));
  for (float r : scan.ranges) {
    uint16_t v = kCodeInvalid;
    if (IsReturn(r) && r >= 0.0f) {
      const double units = std::round(static_cast<double>(r) / metres);
      v = units >= kFirstNoReturnCode ? kCodeAboveMaximum : static_cast<uint16_t>(units);
    }
    PutU16(&d, v);
  }
  return EncodeTelegram(kScannerAddress, kReplyValues, d, status);
}

}  // namespace atlas::sick
