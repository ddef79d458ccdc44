#pragma once
// SICK LMS 2xx messages (docs/devices.md, section 1): the host commands, the scanner's
// replies, and the measured values (reply 0xB0) as an atlas::LaserScan. Pure functions over
// TelegramView (lms_telegram.h); the encoders produce whole telegrams with CRC, used by the
// driver (host commands) and by the fake scanner (replies).

#include <cstdint>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "core/common/sensor_types.h"
#include "core/common/time.h"
#include "drivers/sick/lms_telegram.h"

namespace atlas::sick {

// Command codes; a reply's code is the request's + 0x80.
inline constexpr uint8_t kCmdMode = 0x20;
inline constexpr uint8_t kCmdRequestValues = 0x30;
inline constexpr uint8_t kCmdStatus = 0x31;
inline constexpr uint8_t kCmdVariant = 0x3B;
inline constexpr uint8_t kReplyMode = 0xA0;
inline constexpr uint8_t kReplyValues = 0xB0;
inline constexpr uint8_t kReplyStatus = 0xB1;
inline constexpr uint8_t kReplyVariant = 0xBB;
inline constexpr uint8_t kReplyIncorrectCommand = 0x92;

// Mode 0x20 data byte.
inline constexpr uint8_t kModeInstallation = 0x00;  // followed by the password "SICK_LMS"
inline constexpr uint8_t kModeContinuous = 0x24;    // continuous output of all values
inline constexpr uint8_t kModeOnRequest = 0x25;     // values on request
inline constexpr std::string_view kInstallationPassword = "SICK_LMS";

enum class Baud : uint8_t { k9600 = 0x42, k19200 = 0x41, k38400 = 0x40, k500000 = 0x48 };
int BaudRate(Baud b);  // 9600, 19200, 38400, 500000
std::optional<Baud> BaudFromRate(int bits_per_second);

// Range unit, bits 14-15 of the count word.
enum class Unit : uint8_t { kCentimetre = 0, kMillimetre = 1 };
double UnitMetres(Unit u);  // 0.01 or 0.001

// Range codes 8183..8191 are "no valid return".
inline constexpr uint16_t kRangeMask = 0x1FFF;
inline constexpr uint16_t kFirstNoReturnCode = 8183;
inline constexpr uint16_t kCodeInvalid = 8191;
inline constexpr uint16_t kCodeAboveMaximum = 8183;

// ---- Host commands (whole telegrams, ADDR 0x00) --------------------------------------------

std::vector<uint8_t> EncodeStatusRequest();                    // 0x31
std::vector<uint8_t> EncodeModeBaud(Baud baud);                // 0x20 0x42/0x41/0x40/0x48
std::vector<uint8_t> EncodeModeContinuous();                   // 0x20 0x24
std::vector<uint8_t> EncodeModeOnRequest();                    // 0x20 0x25
std::vector<uint8_t> EncodeModeInstallation();                 // 0x20 0x00 "SICK_LMS"
std::vector<uint8_t> EncodeVariantRequest(uint16_t angle_deg,  // 0x3B: 180 or 100
                                          uint16_t resolution_centideg);  // 100, 50, 25
std::vector<uint8_t> EncodeScanRequest();                                 // 0x30 0x01

// A host command as the fake scanner understands it.
struct HostCommand {
  enum class Kind {
    kStatus,
    kModeBaud,
    kModeContinuous,
    kModeOnRequest,
    kModeInstallation,  // password checked: a wrong one is kUnknown
    kVariant,
    kScanRequest,
    kUnknown,  // anything else: the scanner answers NAK or 0x92
  };
  Kind kind = Kind::kUnknown;
  Baud baud = Baud::k9600;  // kModeBaud
  uint16_t angle_deg = 0;   // kVariant
  uint16_t resolution_centideg = 0;
};
HostCommand DecodeHostCommand(const TelegramView& t);

// ---- Scanner replies (ADDR 0x80, with STATUS) ----------------------------------------------

// Low nibble of STATUS: 0 ok, 3 error, 4 fatal; bit 7 pollution (window dirty).
enum class StatusLevel { kOk, kError, kFatal, kOther };
struct ScannerStatus {
  uint8_t raw = 0;
  StatusLevel level() const;
  bool pollution() const { return (raw & 0x80) != 0; }
};

// ACK + A0 (data 0x00 = success, else 0x01) + status. E.g. ok, status 0x10:
// 06 02 80 03 00 A0 00 10 16 0A.
std::vector<uint8_t> EncodeModeReply(bool success, uint8_t status);
// ACK + B1. Only the software-version field (7 bytes) is filled; the rest of the 152-byte
// block is zeros (the host checks only that a B1 arrives).
std::vector<uint8_t> EncodeStatusReply(uint8_t status,
                                       std::string_view software_version = "V02.30 ");
// ACK + BB: 0x01 accepted (0x00 rejected) + angle u16 LE + resolution u16 LE + status.
std::vector<uint8_t> EncodeVariantReply(bool accepted, uint16_t angle_deg,
                                        uint16_t resolution_centideg, uint8_t status);
// ACK + 0x92 "incorrect command" + status.
std::vector<uint8_t> EncodeIncorrectCommandReply(uint8_t status);

// Replies as the driver reads them; nullopt when t is not that reply or is malformed.
struct ModeReply {
  bool success = false;
  ScannerStatus status;
};
std::optional<ModeReply> DecodeModeReply(const TelegramView& t);
struct StatusReply {
  std::string software_version;  // 7 characters, trailing blanks/NULs removed
  ScannerStatus status;
};
std::optional<StatusReply> DecodeStatusReply(const TelegramView& t);
struct VariantReply {
  bool accepted = false;
  uint16_t angle_deg = 0;
  uint16_t resolution_centideg = 0;
  ScannerStatus status;
};
std::optional<VariantReply> DecodeVariantReply(const TelegramView& t);

// ---- Measured values, reply 0xB0 -----------------------------------------------------------
//   B0 | count word (u16 LE) | N x range (u16 LE) | STATUS
// Count word: bits 0-9 N, bits 11-12 partial-scan index, bit 13 scan type, bits 14-15 unit.

struct ScanOptions {
  Pose2 sensor_pose;  // the scanner on the robot, copied into LaserScan::sensor_pose
};

enum class ScanDecode {
  kOk,
  kNotMeasuredValues,  // command is not 0xB0, or no STATUS byte
  kLengthMismatch,     // data is not 2 + 2N bytes
  kBadUnit,            // unit bits 10 or 11
  kUnsupportedCount,   // N not one of 181, 361 (180 deg) or 101, 201, 401 (100 deg)
};

struct ScanInfo {
  int count = 0;
  int partial_scan = 0;  // bits 11-12; reported, the angles are not shifted
  bool scan_type = false;
  Unit unit = Unit::kCentimetre;
  ScannerStatus status;
  int no_return_beams = 0;
};

// Decodes a 0xB0 reply into `scan` (stamped with `stamp`, the arrival time the caller measured).
// Beam i is at angle_min + i * angle_increment, counter-clockwise, the first at -90 deg
// (180-degree scans) or -50 deg (100-degree scans). Ranges are (value & 0x1FFF) * unit in
// metres; codes 8183..8191 are kNoReturn. max_range is 8182 units. `scan` is written only on kOk
// (its ranges vector is reused, so a steady stream does not allocate).
ScanDecode DecodeMeasuredValues(const TelegramView& t, Time stamp, const ScanOptions& options,
                                LaserScan* scan, ScanInfo* info);

// B0 reply for the fake scanner: ranges rounded to the nearest `unit`; kNoReturn, NaN and
// negative ranges become 8191 (invalid), ranges of 8183 units or more become 8183 (above
// maximum). Fails (nullopt) when the scan has no beams or more than 404 (LEN would pass 812).
// No ACK in front (continuous output); prepend kAck when answering a 0x30 request.
std::optional<std::vector<uint8_t>> EncodeMeasuredValues(const LaserScan& scan, Unit unit,
                                                         uint8_t status);

}  // namespace atlas::sick
