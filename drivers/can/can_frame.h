#pragma once
// A classic CAN frame as a plain value, mirroring the fields of Linux's `struct can_frame`
// (can_frame_linux.h converts; the fake bus sends that struct as one 16-byte datagram).
// No socket types here.

#include <array>
#include <cstdint>

namespace atlas {

inline constexpr uint32_t kCanEffFlag = 0x80000000u;  // extended (29-bit) identifier
inline constexpr uint32_t kCanRtrFlag = 0x40000000u;  // remote transmission request
inline constexpr uint32_t kCanErrFlag = 0x20000000u;  // error frame (SocketCAN)
inline constexpr uint32_t kCanSffMask = 0x000007FFu;
inline constexpr uint32_t kCanEffMask = 0x1FFFFFFFu;

struct CanFrame {
  uint32_t id = 0;  // identifier with the EFF/RTR/ERR flag bits, host order
  uint8_t dlc = 0;  // payload length, 0..8
  std::array<uint8_t, 8> data{};

  bool is_error() const { return (id & kCanErrFlag) != 0; }
  bool is_extended() const { return (id & kCanEffFlag) != 0; }
  bool is_remote() const { return (id & kCanRtrFlag) != 0; }
  // A standard (11-bit) data frame: the only kind the AgileX protocol uses.
  bool is_standard_data() const { return (id & (kCanErrFlag | kCanEffFlag | kCanRtrFlag)) == 0; }
  uint32_t standard_id() const { return id & kCanSffMask; }
  friend bool operator==(const CanFrame&, const CanFrame&) = default;
};

}  // namespace atlas
