#include "drivers/agilex/agilex_messages.h"

namespace atlas::agilex {
namespace {

uint32_t U32Be(const std::array<uint8_t, 8>& d, int at) {
  return (static_cast<uint32_t>(d[at]) << 24) | (static_cast<uint32_t>(d[at + 1]) << 16) |
         (static_cast<uint32_t>(d[at + 2]) << 8) | static_cast<uint32_t>(d[at + 3]);
}
uint16_t U16Be(const std::array<uint8_t, 8>& d, int at) {
  return static_cast<uint16_t>((d[at] << 8) | d[at + 1]);
}
void PutU32Be(std::array<uint8_t, 8>* d, int at, uint32_t v) {
  for (int i = 0; i < 4; ++i) (*d)[at + i] = static_cast<uint8_t>(v >> (24 - 8 * i));
}
void PutU16Be(std::array<uint8_t, 8>* d, int at, uint16_t v) {
  (*d)[at] = static_cast<uint8_t>(v >> 8);
  (*d)[at + 1] = static_cast<uint8_t>(v & 0xFF);
}

CanFrame Standard(uint32_t id) {
  CanFrame f;
  f.id = id;
  f.dlc = 8;
  return f;
}

}  // namespace

Message DecodeFrame(const CanFrame& frame) {
  Message m;
  if (frame.is_error()) {
    m.kind = FrameKind::kErrorFrame;
    return m;
  }
  if (!frame.is_standard_data()) {
    m.kind = FrameKind::kNotStandardData;
    return m;
  }
  const auto& d = frame.data;
  switch (frame.standard_id()) {
    case kOdometryId:
      if (frame.dlc != 8) break;
      m.kind = FrameKind::kOdometry;
      m.odometry.left_mm = static_cast<int32_t>(U32Be(d, 0));
      m.odometry.right_mm = static_cast<int32_t>(U32Be(d, 4));
      return m;
    case kMotionStateId:
      if (frame.dlc < 4 || frame.dlc > 8) break;
      m.kind = FrameKind::kMotionState;
      m.motion.linear_mm_s = static_cast<int16_t>(U16Be(d, 0));
      m.motion.angular_mrad_s = static_cast<int16_t>(U16Be(d, 2));
      return m;
    case kSystemStateId:
      if (frame.dlc != 8) break;
      m.kind = FrameKind::kSystemState;
      m.system.vehicle_state = d[0];
      m.system.control_mode = d[1];
      m.system.battery_dv = U16Be(d, 2);
      m.system.fault_bits = d[4];
      m.system.rolling_count = d[7];
      return m;
    default:
      m.kind = FrameKind::kUnknownId;
      return m;
  }
  m.kind = FrameKind::kBadLength;
  return m;
}

CanFrame EncodeOdometry(const WheelDistances& w) {
  CanFrame f = Standard(kOdometryId);
  PutU32Be(&f.data, 0, static_cast<uint32_t>(w.left_mm));
  PutU32Be(&f.data, 4, static_cast<uint32_t>(w.right_mm));
  return f;
}

CanFrame EncodeMotionState(const MotionState& m) {
  CanFrame f = Standard(kMotionStateId);
  PutU16Be(&f.data, 0, static_cast<uint16_t>(m.linear_mm_s));
  PutU16Be(&f.data, 2, static_cast<uint16_t>(m.angular_mrad_s));
  return f;
}

CanFrame EncodeSystemState(const SystemState& s) {
  CanFrame f = Standard(kSystemStateId);
  f.data[0] = s.vehicle_state;
  f.data[1] = s.control_mode;
  PutU16Be(&f.data, 2, s.battery_dv);
  f.data[4] = s.fault_bits;
  f.data[7] = s.rolling_count;
  return f;
}

}  // namespace atlas::agilex
