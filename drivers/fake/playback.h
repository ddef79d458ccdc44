#pragma once
// What the fake devices play: a recording (scans and odometry poses, from a CARMEN log or a
// simulated run) and one playback clock shared by all fake devices of a run, so that they stay
// in step. Log time maps to wall time as  wall = start + (log - log_start) / speed.
// Nothing plays before Start(): a test can open the drivers first, then start the clock.

#include <atomic>
#include <cstddef>
#include <memory>
#include <string>
#include <vector>

#include "core/common/sensor_types.h"

namespace atlas::fake {

struct Recording {
  std::vector<LaserScan> scans;          // stamps in log time, increasing
  std::vector<OdometrySample> odometry;  // stamps in log time, increasing
  Time begin{};                          // earliest stamp
  Time end{};                            // latest stamp
  // The odometry pose at log time t, linearly interpolated (angles along the short way),
  // clamped at both ends. The recording must have odometry.
  Pose2 OdometryAt(Time t) const;
};

// Reads a CARMEN log (plain or gzip) into a Recording. `max_scans` > 0 keeps only the first
// scans and the odometry up to the last kept scan. On failure returns false with *error.
bool LoadCarmenRecording(const std::string& path, size_t max_scans, Recording* out,
                         std::string* error);

class PlaybackClock {
 public:
  // speed: 1 = real time, 10 = ten times faster. Must be > 0.
  PlaybackClock(Time log_start, double speed) : log_start_(log_start), speed_(speed) {}
  void Start() { StartAt(Now()); }
  void StartAt(Time wall) {
    wall_start_ns_.store(wall.time_since_epoch().count(), std::memory_order_release);
  }
  bool started() const { return wall_start_ns_.load(std::memory_order_acquire) != 0; }
  double speed() const { return speed_; }
  Time log_start() const { return log_start_; }
  // Only meaningful once started.
  Time WallAt(Time log) const {
    return Time(Duration(wall_start_ns_.load(std::memory_order_acquire))) +
           Duration(static_cast<int64_t>(static_cast<double>((log - log_start_).count()) / speed_));
  }
  Time LogAt(Time wall) const {
    return log_start_ +
           Duration(static_cast<int64_t>(
               static_cast<double>(
                   (wall - Time(Duration(wall_start_ns_.load(std::memory_order_acquire))))
                       .count()) *
               speed_));
  }

 private:
  Time log_start_;
  double speed_;
  std::atomic<int64_t> wall_start_ns_{0};
};

}  // namespace atlas::fake
