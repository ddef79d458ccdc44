#include "drivers/fake/fault_options.h"

#include <cmath>

namespace atlas::fake {

std::string FaultOptions::Validate() const {
  if (garbage_every < 0 || corrupt_crc_every < 0 || truncate_every < 0 || jump_every < 0)
    return "faults: the *_every counts must be >= 0";
  if (garbage_bytes < 1 || garbage_bytes > 4096) return "faults: garbage_bytes must be 1..4096";
  if (!std::isfinite(drop_after_s) || !std::isfinite(drop_for_s) || !std::isfinite(stall_after_s) ||
      !std::isfinite(stall_for_s))
    return "faults: the drop and stall times must be finite";
  if (drop_after_s >= 0 && drop_for_s <= 0) return "faults: drop_for_s must be > 0";
  if (stall_after_s >= 0 && stall_for_s <= 0) return "faults: stall_for_s must be > 0";
  if (drop_after_s < 0 && drop_for_s != 0)
    return "faults: drop_for_s without drop_after_s (drop_after_s < 0 means no drop)";
  if (stall_after_s < 0 && stall_for_s != 0)
    return "faults: stall_for_s without stall_after_s (stall_after_s < 0 means no stall)";
  return "";
}

bool FaultOptions::any() const {
  return garbage_every > 0 || corrupt_crc_every > 0 || truncate_every > 0 || jump_every > 0 ||
         drop_after_s >= 0 || stall_after_s >= 0;
}

std::string GarbageBytes(int n, uint32_t seed) {
  std::string s;
  uint32_t x = seed * 2654435761u + 12345u;
  for (int i = 0; i < n; ++i) {
    x = x * 1664525u + 1013904223u;
    uint8_t b = static_cast<uint8_t>(x >> 24);
    if (b == 0x02 || b == 0xFA || b == 0x06 || b == 0x15) b ^= 0x40;
    s.push_back(static_cast<char>(b));
  }
  return s;
}

}  // namespace atlas::fake
