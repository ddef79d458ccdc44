#pragma once
// AgileX mobile-base CAN protocol v2 (docs/devices.md, section 2): pure decoders and
// encoders of the frames atlasd reads. Standard 11-bit identifiers, fields big-endian.
//
//   0x311 odometry      bytes 0-3 int32 left wheel distance mm, 4-7 int32 right (cumulative)
//   0x221 motion state  bytes 0-1 int16 linear 0.001 m/s, 2-3 int16 angular 0.001 rad/s
//   0x211 system state  byte 0 vehicle state (0 normal), 1 control mode, 2-3 u16 battery
//                       0.1 V, 4 fault bits, 7 rolling count
// Example: left 1000 mm, right -2 mm -> id 0x311, 00 00 03 E8 FF FF FF FE.

#include <cstdint>

#include "drivers/can/can_frame.h"

namespace atlas::agilex {

inline constexpr uint32_t kSystemStateId = 0x211;
inline constexpr uint32_t kMotionStateId = 0x221;
inline constexpr uint32_t kOdometryId = 0x311;
// The base sends 0x311 and 0x221 every 20 ms (docs/devices.md, section 3).
inline constexpr double kFramePeriodS = 0.02;

struct WheelDistances {  // 0x311
  int32_t left_mm = 0;
  int32_t right_mm = 0;
  friend bool operator==(const WheelDistances&, const WheelDistances&) = default;
};

struct MotionState {           // 0x221
  int16_t linear_mm_s = 0;     // 0.001 m/s
  int16_t angular_mrad_s = 0;  // 0.001 rad/s
  double linear_mps() const { return linear_mm_s * 1e-3; }
  double angular_radps() const { return angular_mrad_s * 1e-3; }
  friend bool operator==(const MotionState&, const MotionState&) = default;
};

struct SystemState {          // 0x211
  uint8_t vehicle_state = 0;  // 0 = normal
  uint8_t control_mode = 0;
  uint16_t battery_dv = 0;  // 0.1 V
  uint8_t fault_bits = 0;
  uint8_t rolling_count = 0;  // byte 7
  double battery_volts() const { return battery_dv * 0.1; }
  friend bool operator==(const SystemState&, const SystemState&) = default;
};

enum class FrameKind {
  kOdometry,
  kMotionState,
  kSystemState,
  kUnknownId,        // a standard data frame with another id: ignore
  kBadLength,        // a known id with too few bytes (or dlc > 8)
  kNotStandardData,  // extended or remote frame
  kErrorFrame,       // SocketCAN error frame (bus-off, controller problems): report
};

struct Message {
  FrameKind kind = FrameKind::kUnknownId;
  WheelDistances odometry;  // kOdometry
  MotionState motion;       // kMotionState
  SystemState system;       // kSystemState
};

// Needs dlc >= 8 for 0x311 and 0x211, >= 4 for 0x221.
Message DecodeFrame(const CanFrame& frame);

// Frames as the base sends them (dlc 8, reserved bytes zero).
CanFrame EncodeOdometry(const WheelDistances& d);
CanFrame EncodeMotionState(const MotionState& m);
CanFrame EncodeSystemState(const SystemState& s);

}  // namespace atlas::agilex
