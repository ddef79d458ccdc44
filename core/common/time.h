#pragma once
// The one time type of atlasd: a point on a monotonic clock, in nanoseconds.
//
// Live data is stamped with CLOCK_MONOTONIC at arrival (kernel timestamps where a device gives
// them). Logged data keeps the log's clock: a log's timestamps are mapped onto the same type so
// that replay and live runs go through the same code. Never mix the two in one run.

#include <chrono>
#include <cstdint>

namespace atlas {

using Duration = std::chrono::nanoseconds;
using Time = std::chrono::time_point<std::chrono::steady_clock, Duration>;

// The time of CLOCK_MONOTONIC now.
inline Time Now() {
  return std::chrono::time_point_cast<Duration>(std::chrono::steady_clock::now());
}

inline Time FromSeconds(double seconds) {
  return Time(Duration(static_cast<int64_t>(seconds * 1e9 + (seconds >= 0 ? 0.5 : -0.5))));
}

inline double ToSeconds(Duration d) { return static_cast<double>(d.count()) * 1e-9; }
inline double ToSeconds(Time t) { return ToSeconds(t.time_since_epoch()); }

// t truncated to a whole multiple of `resolution` since the epoch (toward the epoch, as integer
// division truncates); a resolution of zero or less keeps t.
inline Time Truncate(Time t, Duration resolution) {
  if (resolution <= Duration::zero()) return t;
  return Time(t.time_since_epoch() / resolution * resolution);
}

}  // namespace atlas
