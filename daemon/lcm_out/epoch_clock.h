#pragma once
// utime on LCM: microseconds since the Unix epoch, as bot_core's types and lcm-logger stamp
// messages, so that atlasd's messages line up with other hosts' and with other logs. Inside
// atlasd every stamp stays on the monotonic clock (core/common/time.h); the offset between the
// two clocks (CLOCK_REALTIME - CLOCK_MONOTONIC) is captured once at start and applied only where
// messages leave (AtlasPublisher) and where a reader of atlasd's messages needs its monotonic
// stamps back (atlas-pose-latency, the latency benchmark).
//
// Both clocks are slewed alike by NTP, so the offset holds until the system clock is stepped
// (settimeofday, a large NTP correction): a capture made later by another process converts
// atlasd's utimes exactly, to the microsecond of the captures, unless a step came between them.
// A running atlasd keeps its offset across a step: its utimes stay as steady as its stamps.
// Replaying a recording (atlasd --replay, atlas-replay) keeps the recording's clock: its stamps
// are then seconds since the epoch.

#include <time.h>

#include <cstdint>

#include "core/common/time.h"

namespace atlas {

class EpochClock {
 public:
  // Offset 0: utime is the monotonic clock's microseconds (tests).
  EpochClock() = default;
  explicit EpochClock(int64_t offset_us) : offset_us_(offset_us) {}

  // The offset now: CLOCK_REALTIME read between two readings of CLOCK_MONOTONIC, the closest of
  // a few tries, against their midpoint; whole microseconds.
  static EpochClock Capture() {
    int64_t best_gap = INT64_MAX, offset_ns = 0;
    for (int i = 0; i < 5; ++i) {
      const int64_t a = Read(CLOCK_MONOTONIC), real = Read(CLOCK_REALTIME),
                    b = Read(CLOCK_MONOTONIC);
      if (b - a < best_gap) {
        best_gap = b - a;
        offset_ns = real - (a + (b - a) / 2);
      }
    }
    return EpochClock(offset_ns / 1000);
  }

  int64_t offset_us() const { return offset_us_; }
  // A utime on the monotonic clock (ToUtime of a stamp) as microseconds since the epoch, and
  // back. Exact inverses.
  int64_t ToEpoch(int64_t monotonic_utime) const { return monotonic_utime + offset_us_; }
  int64_t ToMonotonic(int64_t epoch_utime) const { return epoch_utime - offset_us_; }
  // A stamp as a published utime, and a published utime as the stamp it was (whole
  // microseconds, as the raw channels carry them).
  int64_t Utime(Time stamp) const { return ToEpoch(stamp.time_since_epoch().count() / 1000); }
  Time Stamp(int64_t epoch_utime) const {
    return Time(std::chrono::microseconds(ToMonotonic(epoch_utime)));
  }

 private:
  static int64_t Read(clockid_t clock) {
    timespec t{};
    clock_gettime(clock, &t);
    return static_cast<int64_t>(t.tv_sec) * 1000000000 + t.tv_nsec;
  }

  int64_t offset_us_ = 0;
};

}  // namespace atlas
