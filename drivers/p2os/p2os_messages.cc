#include "drivers/p2os/p2os_messages.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <numbers>

namespace atlas::p2os {
namespace {

// Reads little-endian fields; the caller has checked the length.
class LittleEndianReader {
 public:
  explicit LittleEndianReader(std::span<const uint8_t> b) : b_(b) {}
  uint8_t U8() { return b_[at_++]; }
  uint16_t U16() {
    const uint16_t v = static_cast<uint16_t>(b_[at_] | (b_[at_ + 1] << 8));
    at_ += 2;
    return v;
  }
  int16_t I16() { return static_cast<int16_t>(U16()); }

 private:
  std::span<const uint8_t> b_;
  std::size_t at_ = 0;
};

void PutU16(std::vector<uint8_t>* out, uint16_t v) {
  out->push_back(static_cast<uint8_t>(v & 0xFF));
  out->push_back(static_cast<uint8_t>(v >> 8));
}

constexpr std::size_t kSipFixedBefore = 20;  // type .. sonar count
constexpr std::size_t kSipFixedAfter = 5;    // timer, analog, digin, digout
constexpr std::size_t kMaxSipSonars = (kMaxPayload - kSipFixedBefore - kSipFixedAfter) / 3;

SonarTransducer Transducer(double x_mm, double y_mm, double heading_deg) {
  SonarTransducer t;
  t.pose = Pose2{x_mm * 1e-3, y_mm * 1e-3, WrapAngle(heading_deg * std::numbers::pi / 180.0)};
  return t;
}

}  // namespace

std::vector<uint8_t> EncodeSync(int n) {
  const std::array<uint8_t, 1> p{static_cast<uint8_t>(n)};
  return EncodePacket(p);
}

std::vector<uint8_t> EncodeCommand(uint8_t command) {
  const std::array<uint8_t, 1> p{command};
  return EncodePacket(p);
}

std::vector<uint8_t> EncodeCommandInt(uint8_t command, int value) {
  const int magnitude = std::min(std::abs(value), 0xFFFF);
  const std::array<uint8_t, 4> p{command, value < 0 ? kArgNegativeInt : kArgPositiveInt,
                                 static_cast<uint8_t>(magnitude & 0xFF),
                                 static_cast<uint8_t>(magnitude >> 8)};
  return EncodePacket(p);
}

std::vector<uint8_t> EncodeOpen() { return EncodeCommand(kCmdOpen); }
std::vector<uint8_t> EncodePulse() { return EncodeCommand(kCmdPulse); }
std::vector<uint8_t> EncodeSonarOn() { return EncodeCommandInt(kCmdSonar, 1); }

std::optional<HostCommand> DecodeHostCommand(const PacketView& p) {
  if (p.payload.size() == 1) return HostCommand{p.payload[0], std::nullopt};
  if (p.payload.size() == 4 &&
      (p.payload[1] == kArgPositiveInt || p.payload[1] == kArgNegativeInt)) {
    const int magnitude = p.payload[2] | (p.payload[3] << 8);
    return HostCommand{p.payload[0], p.payload[1] == kArgNegativeInt ? -magnitude : magnitude};
  }
  return std::nullopt;
}

std::optional<int> SyncEcho(const PacketView& p) {
  if (p.payload.size() == 1 && p.payload[0] <= kCmdSync2) return p.payload[0];
  if (p.payload.size() > 1 && p.payload[0] == kCmdSync2) return 2;
  return std::nullopt;
}

std::optional<RobotIdentity> DecodeSync2Reply(const PacketView& p) {
  if (p.payload.size() < 2 || p.payload[0] != kCmdSync2) return std::nullopt;
  std::array<std::string, 3> fields;
  std::size_t field = 0;
  for (std::size_t i = 1; i < p.payload.size() && field < fields.size(); ++i) {
    if (p.payload[i] == 0) {
      ++field;
    } else {
      fields[field].push_back(static_cast<char>(p.payload[i]));
    }
  }
  return RobotIdentity{fields[0], fields[1], fields[2]};
}

std::vector<uint8_t> EncodeSyncReply(int n) { return EncodeSync(n); }

std::vector<uint8_t> EncodeSync2Reply(const RobotIdentity& id) {
  std::vector<uint8_t> p{kCmdSync2};
  for (const std::string* s : {&id.name, &id.robot_class, &id.subclass}) {
    // Each field is cut so that the three always fit in one packet.
    const std::size_t n = std::min<std::size_t>(s->size(), 80);
    p.insert(p.end(), s->begin(), s->begin() + static_cast<std::ptrdiff_t>(n));
    p.push_back(0);
  }
  return EncodePacket(p);
}

SipDecode DecodeStandardSip(const PacketView& p, StandardSip* sip) {
  if (p.payload.empty() || !IsStandardSipType(p.payload[0])) return SipDecode::kNotStandardSip;
  if (p.payload.size() < kSipFixedBefore) return SipDecode::kTruncated;
  const std::size_t count = p.payload[kSipFixedBefore - 1];
  if (p.payload.size() < kSipFixedBefore + 3 * count + kSipFixedAfter) {
    return SipDecode::kTruncated;
  }
  LittleEndianReader r(p.payload);
  StandardSip s;
  s.sonars = std::move(sip->sonars);
  s.sonars.clear();
  s.type = r.U8();
  s.xpos = r.U16();
  s.ypos = r.U16();
  s.th = r.I16();
  s.lvel = r.I16();
  s.rvel = r.I16();
  s.battery_dv = r.U8();
  s.stall_left = r.U8();
  s.stall_right = r.U8();
  s.control = r.I16();
  s.flags = r.U16();
  s.compass = r.U8();
  r.U8();  // the sonar count, read above
  for (std::size_t i = 0; i < count; ++i) {
    SonarRaw raw;
    raw.index = r.U8();
    raw.range = r.U16();
    s.sonars.push_back(raw);
  }
  s.timer = r.U16();
  s.analog = r.U8();
  s.digin = r.U8();
  s.digout = r.U8();
  *sip = std::move(s);
  return SipDecode::kOk;
}

std::optional<std::vector<uint8_t>> EncodeStandardSip(const StandardSip& s) {
  if (s.sonars.size() > kMaxSipSonars) return std::nullopt;
  std::vector<uint8_t> p;
  p.reserve(kSipFixedBefore + 3 * s.sonars.size() + kSipFixedAfter);
  p.push_back(s.type);
  PutU16(&p, s.xpos);
  PutU16(&p, s.ypos);
  PutU16(&p, static_cast<uint16_t>(s.th));
  PutU16(&p, static_cast<uint16_t>(s.lvel));
  PutU16(&p, static_cast<uint16_t>(s.rvel));
  p.push_back(s.battery_dv);
  p.push_back(s.stall_left);
  p.push_back(s.stall_right);
  PutU16(&p, static_cast<uint16_t>(s.control));
  PutU16(&p, s.flags);
  p.push_back(s.compass);
  p.push_back(static_cast<uint8_t>(s.sonars.size()));
  for (const SonarRaw& raw : s.sonars) {
    p.push_back(raw.index);
    PutU16(&p, raw.range);
  }
  PutU16(&p, s.timer);
  p.push_back(s.analog);
  p.push_back(s.digin);
  p.push_back(s.digout);
  return EncodePacket(p);
}

std::vector<SonarTransducer> P3dxSonarRing() {
  return {
      Transducer(69, 136, 90),      Transducer(114, 119, 50),    Transducer(148, 78, 30),
      Transducer(166, 27, 10),      Transducer(166, -27, -10),   Transducer(148, -78, -30),
      Transducer(114, -119, -50),   Transducer(69, -136, -90),   Transducer(-157, -136, -90),
      Transducer(-203, -119, -130), Transducer(-237, -78, -150), Transducer(-255, -27, -170),
      Transducer(-255, 27, 170),    Transducer(-237, 78, 150),   Transducer(-203, 119, 130),
      Transducer(-157, 136, 90),
  };
}

std::vector<SonarTransducer> B21SonarRing() {
  constexpr int kCount = 24;
  constexpr double kRadiusMm = 260.0;
  std::vector<SonarTransducer> ring;
  ring.reserve(kCount);
  for (int i = 0; i < kCount; ++i) {
    const double deg = 360.0 * i / kCount;
    const double rad = deg * std::numbers::pi / 180.0;
    ring.push_back(Transducer(kRadiusMm * std::cos(rad), kRadiusMm * std::sin(rad), deg));
  }
  return ring;
}

std::string SonarOptions::Validate() const {
  if (!(range_factor_mm > 0.0) || !std::isfinite(range_factor_mm)) {
    return "range_factor_mm must be a positive number of millimetres per range unit";
  }
  if (ring.empty()) return "the sonar ring has no transducers";
  if (ring.size() > 256) return "the sonar ring has more than 256 transducers (index is a byte)";
  for (const SonarTransducer& t : ring) {
    if (!(t.max_range > 0.0) || !std::isfinite(t.max_range)) {
      return "every transducer needs a positive max_range in metres";
    }
  }
  return {};
}

SonarConversion ToSonarReading(const StandardSip& sip, Time stamp, const SonarOptions& options,
                               SonarReading* reading) {
  SonarConversion c;
  reading->stamp = stamp;
  reading->returns.clear();
  for (const SonarRaw& raw : sip.sonars) {
    if (raw.index >= options.ring.size()) {
      ++c.unknown_transducer;
      continue;
    }
    const double metres = raw.range * options.range_factor_mm * 1e-3;
    SonarReturn out;
    out.transducer = raw.index;
    if (metres >= options.ring[raw.index].max_range) {
      ++c.no_return;
      out.range = kNoReturn;
    } else {
      out.range = static_cast<float>(metres);
    }
    reading->returns.push_back(out);
    ++c.returns;
  }
  return c;
}

std::vector<SonarRaw> ToSonarRaw(const SonarReading& reading, const SonarOptions& options) {
  std::vector<SonarRaw> out;
  for (const SonarReturn& r : reading.returns) {
    if (r.transducer < 0 || static_cast<std::size_t>(r.transducer) >= options.ring.size()) continue;
    const double max_range = options.ring[static_cast<std::size_t>(r.transducer)].max_range;
    double units = 0.0;
    if (!IsReturn(r.range) || r.range >= max_range) {
      units = std::ceil(max_range * 1e3 / options.range_factor_mm);
    } else {
      units = std::round(std::max(0.0f, r.range) * 1e3 / options.range_factor_mm);
    }
    out.push_back(SonarRaw{static_cast<uint8_t>(r.transducer),
                           static_cast<uint16_t>(std::min(units, 65535.0))});
  }
  return out;
}

}  // namespace atlas::p2os
