// libFuzzer target: the input as a sequence of 16-byte `struct can_frame`s (as the fake bus
// delivers them), each decoded and re-encoded; odometry frames drive the wheel-odometry
// integrator with stamps taken from the input. Invariants are checked with traps.

#include <cmath>
#include <cstddef>
#include <cstdint>
#include <cstring>

#include "drivers/agilex/agilex_messages.h"
#include "drivers/agilex/wheel_odometry.h"
#include "drivers/can/can_frame_linux.h"
#include "drivers/framing/fuzz_check.h"

namespace {

using namespace atlas::agilex;

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, std::size_t size) {
  WheelOdometryIntegrator integrator{WheelOdometryOptions{}};
  atlas::Time stamp{};
  uint64_t odometry_frames = 0;
  for (std::size_t at = 0; at + sizeof(struct can_frame) <= size; at += sizeof(struct can_frame)) {
    struct can_frame raw;
    std::memcpy(&raw, data + at, sizeof(raw));
    const atlas::CanFrame frame = atlas::FromLinuxCanFrame(raw);
    const Message m = DecodeFrame(frame);
    switch (m.kind) {
      case FrameKind::kOdometry: {
        FUZZ_CHECK(DecodeFrame(EncodeOdometry(m.odometry)).odometry == m.odometry);
        // The pad bytes carry the time step in ms (0..65535).
        stamp += std::chrono::milliseconds(data[at + 5] | (data[at + 6] << 8));
        const atlas::Pose2 before = integrator.sample().pose;
        const OdometryStep step = integrator.Update(stamp, m.odometry);
        const atlas::Pose2 after = integrator.sample().pose;
        FUZZ_CHECK(after.IsFinite());
        if (step != OdometryStep::kIntegrated) {
          FUZZ_CHECK(before.x == after.x && before.y == after.y && before.theta == after.theta);
        }
        ++odometry_frames;
        break;
      }
      case FrameKind::kMotionState:
        FUZZ_CHECK(DecodeFrame(EncodeMotionState(m.motion)).motion == m.motion);
        FUZZ_CHECK(std::abs(m.motion.linear_mps()) <= 32.768);
        break;
      case FrameKind::kSystemState:
        FUZZ_CHECK(DecodeFrame(EncodeSystemState(m.system)).system == m.system);
        break;
      case FrameKind::kBadLength:
        FUZZ_CHECK(frame.is_standard_data());
        break;
      case FrameKind::kErrorFrame:
        FUZZ_CHECK(frame.is_error());
        break;
      case FrameKind::kNotStandardData:
      case FrameKind::kUnknownId:
        break;
    }
    const atlas::CanFrame back = atlas::FromLinuxCanFrame(atlas::ToLinuxCanFrame(frame));
    FUZZ_CHECK(back.id == frame.id);
  }
  FUZZ_CHECK(integrator.updates() == odometry_frames);
  FUZZ_CHECK(integrator.discontinuities() <= odometry_frames);
  return 0;
}
