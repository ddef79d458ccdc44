#pragma once
// P2OS commands, SYNC handshake and standard SIPs (docs/devices.md, section 3), and the
// conversion of a SIP's sonar returns to an atlas::SonarReading. Pure functions over packet
// payloads (p2os_packet.h); the encoders give whole packets.

#include <cstdint>
#include <optional>
#include <span>
#include <string>
#include <vector>

#include "core/common/sensor_types.h"
#include "core/common/time.h"
#include "drivers/p2os/p2os_packet.h"

namespace atlas::p2os {

// Command numbers.
inline constexpr uint8_t kCmdSync0 = 0;
inline constexpr uint8_t kCmdSync1 = 1;
inline constexpr uint8_t kCmdSync2 = 2;
inline constexpr uint8_t kCmdPulse = 0;
inline constexpr uint8_t kCmdOpen = 1;
inline constexpr uint8_t kCmdClose = 2;
inline constexpr uint8_t kCmdEnable = 4;
inline constexpr uint8_t kCmdSonar = 28;
// Argument types.
inline constexpr uint8_t kArgPositiveInt = 0x3B;
inline constexpr uint8_t kArgNegativeInt = 0x1B;

// ---- Host side ----------------------------------------------------------------------------
std::vector<uint8_t> EncodeSync(int n);               // n = 0, 1, 2: FA FB 03 0n 00 0n
std::vector<uint8_t> EncodeCommand(uint8_t command);  // no argument (OPEN, PULSE, CLOSE)
// Integer argument: 0x3B and |value| as u16 LE, or 0x1B for a negative value.
// E.g. EncodeCommandInt(kCmdEnable, 1) == FA FB 06 04 3B 01 00 05 3B.
std::vector<uint8_t> EncodeCommandInt(uint8_t command, int value);  // |value| <= 65535 (clamped)
std::vector<uint8_t> EncodeOpen();
std::vector<uint8_t> EncodePulse();
std::vector<uint8_t> EncodeSonarOn();  // command 28, argument 1

// A host packet as the fake controller understands it.
struct HostCommand {
  uint8_t command = 0;
  std::optional<int> argument;  // integer argument, sign applied
};
std::optional<HostCommand> DecodeHostCommand(const PacketView& p);

// ---- Controller side: SYNC echoes --------------------------------------------------------
struct RobotIdentity {
  std::string name;
  std::string robot_class;
  std::string subclass;
  friend bool operator==(const RobotIdentity&, const RobotIdentity&) = default;
};
// 0, 1 or 2 when p is the echo of that SYNC (SYNC2's echo carries the identity), else nullopt.
std::optional<int> SyncEcho(const PacketView& p);
// SYNC2 reply: payload 0x02, then name, class, subclass, each NUL-terminated (a missing last
// NUL is tolerated). nullopt when p is not a SYNC2 reply.
std::optional<RobotIdentity> DecodeSync2Reply(const PacketView& p);
std::vector<uint8_t> EncodeSyncReply(int n);  // SYNC0/SYNC1 echo (n = 0, 1)
std::vector<uint8_t> EncodeSync2Reply(const RobotIdentity& id);

// ---- Controller side: standard SIP (type 0x30..0x34) --------------------------------------
// Fields little-endian: type, xpos u16, ypos u16, th i16, lvel i16, rvel i16, battery u8
// (0.1 V), stall/bumpers u8 x2, control i16, flags u16, compass u8, sonar count u8,
// count x {index u8, range u16}, timer u16, analog u8, digin u8, digout u8. Bytes after digout
// (newer firmware) are ignored.
struct SonarRaw {
  uint8_t index = 0;
  uint16_t range = 0;  // controller units
  friend bool operator==(const SonarRaw&, const SonarRaw&) = default;
};
struct StandardSip {
  uint8_t type = 0x32;  // 0x32 stopped, 0x33 moving
  uint16_t xpos = 0;
  uint16_t ypos = 0;
  int16_t th = 0;
  int16_t lvel = 0;
  int16_t rvel = 0;
  uint8_t battery_dv = 0;
  uint8_t stall_left = 0;
  uint8_t stall_right = 0;
  int16_t control = 0;
  uint16_t flags = 0;
  uint8_t compass = 0;
  std::vector<SonarRaw> sonars;  // at most 255
  uint16_t timer = 0;
  uint8_t analog = 0;
  uint8_t digin = 0;
  uint8_t digout = 0;
  friend bool operator==(const StandardSip&, const StandardSip&) = default;
};

enum class SipDecode { kOk, kNotStandardSip, kTruncated };
inline bool IsStandardSipType(uint8_t t) { return t >= 0x30 && t <= 0x34; }
// `sip` is written only on kOk (its sonars vector is reused).
SipDecode DecodeStandardSip(const PacketView& p, StandardSip* sip);
// Whole packet; fails when it would not fit in one packet (more than 76 sonar returns).
std::optional<std::vector<uint8_t>> EncodeStandardSip(const StandardSip& sip);

// ---- Sonar ring ---------------------------------------------------------------------------
// Sixteen transducers of the Pioneer 3-DX (ARIA's p3dx.p: x, y mm, heading deg): front ring
// 0..7 from left (90 deg) to right (-90 deg), rear ring 8..15 from right to left.
std::vector<SonarTransducer> P3dxSonarRing();
// Twenty-four transducers evenly spaced on a ring of radius 0.26 m like the B21's, transducer
// 0 facing forward, numbered counter-clockwise (15 deg apart).
std::vector<SonarTransducer> B21SonarRing();

struct SonarOptions {
  double range_factor_mm = 1.0;  // mm per controller range unit (P3-DX: 1.0)
  std::vector<SonarTransducer> ring = P3dxSonarRing();
  std::string Validate() const;  // empty when valid
};

struct SonarConversion {
  int returns = 0;             // written into the reading
  int no_return = 0;           // range >= the transducer's max_range: kNoReturn
  int unknown_transducer = 0;  // index beyond the ring: dropped
};
// Ranges: range * range_factor_mm / 1000 metres; at or beyond the transducer's max_range they
// are kNoReturn. `reading` is overwritten (its vector reused).
SonarConversion ToSonarReading(const StandardSip& sip, Time stamp, const SonarOptions& options,
                               SonarReading* reading);
// The inverse for the fake controller: a reading's returns as SIP sonar entries (kNoReturn as
// the unit count of the transducer's max_range), rounded to the nearest unit and capped at
// 65535. Returns of unknown transducers are skipped.
std::vector<SonarRaw> ToSonarRaw(const SonarReading& reading, const SonarOptions& options);

}  // namespace atlas::p2os
