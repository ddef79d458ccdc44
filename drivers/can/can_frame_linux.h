#pragma once
// Conversion between atlas::CanFrame and Linux's `struct can_frame` (a POD of 16 bytes:
// can_id u32, len u8, 3 pad bytes, data[8]). Only the code that owns CAN sockets or the fake
// bus includes this header.

#include <linux/can.h>

#include <cstring>

#include "drivers/can/can_frame.h"

namespace atlas {

static_assert(sizeof(struct can_frame) == 16);
static_assert(CAN_EFF_FLAG == kCanEffFlag && CAN_RTR_FLAG == kCanRtrFlag &&
              CAN_ERR_FLAG == kCanErrFlag && CAN_SFF_MASK == kCanSffMask);

inline struct can_frame ToLinuxCanFrame(const CanFrame& f) {
  struct can_frame out;
  std::memset(&out, 0, sizeof(out));
  out.can_id = f.id;
  out.can_dlc = f.dlc > 8 ? 8 : f.dlc;
  std::memcpy(out.data, f.data.data(), 8);
  return out;
}

// A dlc above 8 (possible from a misbehaving peer on the fake bus) is kept as is so that the
// decoder rejects the frame.
inline CanFrame FromLinuxCanFrame(const struct can_frame& f) {
  CanFrame out;
  out.id = f.can_id;
  out.dlc = f.can_dlc;
  std::memcpy(out.data.data(), f.data, 8);
  return out;
}

}  // namespace atlas
