#pragma once
// Fault injection for the fake devices (docs/atlasd.md, "Hardware-in-loop tests"). Counts are in
// messages of the device concerned (LMS telegrams, P2OS SIPs, AgileX 0x311 frames); times are wall
// seconds after the playback clock started. A fake records every fault it injected (FaultCounts),
// so a test can check that the driver counted each one.

#include <atomic>
#include <cstdint>
#include <string>

namespace atlas::fake {

struct FaultOptions {
  int garbage_every = 0;        // before every Nth message, write garbage bytes
  int garbage_bytes = 40;       // how many (never containing a valid frame start)
  int corrupt_crc_every = 0;    // flip the CRC / checksum of every Nth message
  int truncate_every = 0;       // send only the first half of every Nth message
  int jump_every = 0;           // odometry: every Nth 0x311 jumps the counters ...
  int32_t jump_mm = 500000;     // ... by this much (and stays offset, like a base reboot)
  double drop_after_s = -1.0;   // close the device (pty / bus) after this long ...
  double drop_for_s = 0.0;      // ... for this long, then recreate it at the same path
  double stall_after_s = -1.0;  // stop sending anything after this long ...
  double stall_for_s = 0.0;     // ... for this long
  std::string Validate() const;
  bool any() const;
};

struct FaultCounts {
  std::atomic<uint64_t> garbage{0};
  std::atomic<uint64_t> corrupted{0};
  std::atomic<uint64_t> truncated{0};
  std::atomic<uint64_t> jumps{0};
  std::atomic<uint64_t> drops{0};
  std::atomic<uint64_t> stalls{0};
};

// Garbage for a serial line: bytes that cannot start an LMS telegram (no 0x02) nor a P2OS
// packet (no 0xFA), so that what follows is not swallowed.
std::string GarbageBytes(int n, uint32_t seed);

}  // namespace atlas::fake
