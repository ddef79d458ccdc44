#include "drivers/agilex/agilex_messages.h"

#include <gtest/gtest.h>

#include <cstring>

#include "drivers/can/can_frame_linux.h"

namespace atlas::agilex {
namespace {

using Data = std::array<uint8_t, 8>;

CanFrame Frame(uint32_t id, Data data, uint8_t dlc = 8) {
  CanFrame f;
  f.id = id;
  f.dlc = dlc;
  f.data = data;
  return f;
}

TEST(AgilexOdometry, SpecExample) {
  const CanFrame f = EncodeOdometry(WheelDistances{1000, -2});
  EXPECT_EQ(f.id, 0x311u);
  EXPECT_EQ(f.dlc, 8);
  EXPECT_EQ(f.data, (Data{0x00, 0x00, 0x03, 0xE8, 0xFF, 0xFF, 0xFF, 0xFE}));
  const Message m = DecodeFrame(f);
  ASSERT_EQ(m.kind, FrameKind::kOdometry);
  EXPECT_EQ(m.odometry.left_mm, 1000);
  EXPECT_EQ(m.odometry.right_mm, -2);
}

TEST(AgilexOdometry, Int32Extremes) {
  const Message m = DecodeFrame(Frame(0x311, {0x7F, 0xFF, 0xFF, 0xFF, 0x80, 0x00, 0x00, 0x00}));
  ASSERT_EQ(m.kind, FrameKind::kOdometry);
  EXPECT_EQ(m.odometry.left_mm, 2147483647);
  EXPECT_EQ(m.odometry.right_mm, -2147483647 - 1);
  EXPECT_EQ(EncodeOdometry(m.odometry).data, (Data{0x7F, 0xFF, 0xFF, 0xFF, 0x80, 0, 0, 0}));
}

TEST(AgilexMotionState, BigEndianScaledVelocities) {
  const Message m = DecodeFrame(Frame(0x221, {0xFA, 0x24, 0x01, 0x2C, 0, 0, 0, 0}));
  ASSERT_EQ(m.kind, FrameKind::kMotionState);
  EXPECT_EQ(m.motion.linear_mm_s, -1500);
  EXPECT_DOUBLE_EQ(m.motion.linear_mps(), -1.5);
  EXPECT_DOUBLE_EQ(m.motion.angular_radps(), 0.3);
  EXPECT_EQ(EncodeMotionState(m.motion), Frame(0x221, {0xFA, 0x24, 0x01, 0x2C, 0, 0, 0, 0}));
  // Four bytes are enough for the velocities.
  EXPECT_EQ(DecodeFrame(Frame(0x221, {0xFA, 0x24, 0x01, 0x2C}, 4)).kind, FrameKind::kMotionState);
}

TEST(AgilexSystemState, Fields) {
  const Data d{0x00, 0x01, 0x00, 0xFE, 0x02, 0x00, 0x00, 0x07};
  const Message m = DecodeFrame(Frame(0x211, d));
  ASSERT_EQ(m.kind, FrameKind::kSystemState);
  EXPECT_EQ(m.system.vehicle_state, 0);
  EXPECT_EQ(m.system.control_mode, 1);
  EXPECT_EQ(m.system.battery_dv, 254);
  EXPECT_NEAR(m.system.battery_volts(), 25.4, 1e-9);
  EXPECT_EQ(m.system.fault_bits, 2);
  EXPECT_EQ(m.system.rolling_count, 7);
  EXPECT_EQ(EncodeSystemState(m.system).data, d);
}

TEST(AgilexFrames, RejectsWhatIsNotOurs) {
  const Data d{};
  EXPECT_EQ(DecodeFrame(Frame(0x311, d, 7)).kind, FrameKind::kBadLength);
  EXPECT_EQ(DecodeFrame(Frame(0x311, d, 9)).kind, FrameKind::kBadLength);
  EXPECT_EQ(DecodeFrame(Frame(0x211, d, 6)).kind, FrameKind::kBadLength);
  EXPECT_EQ(DecodeFrame(Frame(0x221, d, 3)).kind, FrameKind::kBadLength);
  EXPECT_EQ(DecodeFrame(Frame(0x123, d)).kind, FrameKind::kUnknownId);
  EXPECT_EQ(DecodeFrame(Frame(0x311 | kCanEffFlag, d)).kind, FrameKind::kNotStandardData);
  EXPECT_EQ(DecodeFrame(Frame(0x311 | kCanRtrFlag, d, 0)).kind, FrameKind::kNotStandardData);
  EXPECT_EQ(DecodeFrame(Frame(kCanErrFlag | 0x40, d)).kind, FrameKind::kErrorFrame);
}

TEST(CanFrameLinux, LayoutAndRoundTrip) {
  const CanFrame f = EncodeOdometry(WheelDistances{1000, -2});
  const struct can_frame raw = ToLinuxCanFrame(f);
  uint8_t bytes[16];
  std::memcpy(bytes, &raw, sizeof(bytes));
  uint32_t id = 0;
  std::memcpy(&id, bytes, 4);
  EXPECT_EQ(id, 0x311u);
  EXPECT_EQ(bytes[4], 8);
  EXPECT_EQ(bytes[8 + 3], 0xE8);
  EXPECT_EQ(FromLinuxCanFrame(raw), f);
}

}  // namespace
}  // namespace atlas::agilex
