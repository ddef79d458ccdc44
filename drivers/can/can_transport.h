#pragma once
// Where CAN frames come from: one interface, two implementations chosen by the interface name
// (docs/devices.md, section 2, "SocketCAN and the fake bus"):
//
//   "can0", "vcan1", ...  SocketCAN: socket(PF_CAN, SOCK_RAW, CAN_RAW), a CAN_RAW_FILTER for the
//                         AgileX ids 0x311/0x221/0x211, error frames enabled (CAN_RAW_ERR_FILTER,
//                         handed up as frames with the ERR flag: reported, never fatal), kernel
//                         receive stamps (SO_TIMESTAMP) mapped onto CLOCK_MONOTONIC.
//   "unix:PATH"           the fake bus: a Unix SOCK_SEQPACKET connection to PATH, every datagram
//                         exactly one 16-byte struct can_frame. The fake device listens. Kernel
//                         receive stamps too (SO_TIMESTAMPNS), mapped the same way.
//
// The reader thread is the same for both; only the opening differs. This file owns sockets and
// knows nothing of the AgileX payloads beyond the ids to filter.

#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include "core/common/time.h"
#include "drivers/can/can_frame.h"

namespace atlas {

enum class CanRead {
  kFrame,     // a frame (possibly an error frame: frame.is_error())
  kTimeout,   // nothing within the timeout
  kBadFrame,  // a datagram that is not one struct can_frame (fake bus): counted, skipped
  kNetDown,   // SocketCAN ENETDOWN: the interface is down; the socket stays bound and frames
              // come again once it is up (as candump keeps reading): report, keep reading
  kGone,      // peer closed, ENODEV (interface removed): close and reopen
  kError,     // anything else
};

struct CanReadResult {
  CanRead status = CanRead::kTimeout;
  CanFrame frame;
  Time stamp{};               // arrival: the kernel's stamp when there is one, else Now()
  bool kernel_stamp = false;  // stamp came from the kernel (SO_TIMESTAMP / SO_TIMESTAMPNS)
  std::string error;
};

class CanTransport {
 public:
  virtual ~CanTransport() = default;
  // Opens (or reopens). On failure returns false with a plain-words *error.
  virtual bool Open(std::string* error) = 0;
  virtual void Close() = 0;
  virtual bool is_open() const = 0;
  virtual CanReadResult Read(int timeout_ms) = 0;
  // Sends one frame (used by tests and tools; the AgileX driver only listens).
  virtual bool Write(const CanFrame& frame, std::string* error) = 0;
  virtual const std::string& name() const = 0;
};

// The identifiers the SocketCAN filter lets through.
inline const std::vector<uint32_t>& AgilexFilterIds() {
  static const std::vector<uint32_t> ids = {0x311, 0x221, 0x211};
  return ids;
}

// "unix:PATH" -> fake bus; anything else is a SocketCAN interface name. Never null.
std::unique_ptr<CanTransport> MakeCanTransport(const std::string& interface_name);

// What a SocketCAN read failing with errno `err` means (EAGAIN/EINTR aside).
CanRead CanReadStatusForErrno(int err);

// For tests: the plain-words text for errno `err` when opening `interface_name`.
std::string CanErrnoText(const std::string& interface_name, int err);

}  // namespace atlas
