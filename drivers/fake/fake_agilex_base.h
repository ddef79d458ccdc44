#pragma once
// A fake AgileX mobile base on the fake CAN bus (docs/devices.md, section 2): every
// 20 ms of log time a 0x311 (cumulative wheel distances) and a 0x221 (motion state), every
// 100 ms a 0x211 (system state, rolling count). The wheel distances are those of a
// differential-drive base of the configured track width following the recording's odometry
// poses, interpolated at each 20 ms tick: each tick's relative motion is driven as one arc
// (arc length and turn), accumulated exactly and rounded to whole millimetres only when sent,
// so counter differences over any span are within 1 mm of the true ones.
//
// Faults: jump (the counters jump by jump_mm and stay offset, as after a base reboot), garbage
// (a datagram that is not a can_frame), truncate (a 0x311 with DLC 4), drop (the bus socket
// closes; recreated at the same path), stall (nothing sent).

#include <atomic>
#include <memory>
#include <string>
#include <thread>

#include "drivers/agilex/agilex_messages.h"
#include "drivers/fake/fake_can_bus.h"
#include "drivers/fake/fault_options.h"
#include "drivers/fake/playback.h"
#include "drivers/fake/sent_record.h"

namespace atlas::fake {

struct FakeAgilexOptions {
  std::string socket_path;  // the bus; drivers connect to "unix:" + socket_path
  double track_width_m = 0.58;
  double odometry_period_s = 0.02;  // 0x311 and 0x221, log time
  int system_every = 5;             // 0x211 every 5th tick (100 ms)
  // sent_intact() keeps the last N
  size_t sent_record_capacity = kDefaultSentRecordCapacity;
  FaultOptions faults;
  std::string Validate() const;
};

// One 0x311 the fake sent intact: the tick index, the counters and the recording's pose there.
struct SentOdometry {
  uint64_t tick = 0;
  Time log_time{};
  agilex::WheelDistances counters;
  Pose2 pose;
};

// Wheel distances from a pose path: Advance(pose) drives from the previous pose to `pose` as
// one arc (the exact inverse of the integrator's arc step when the motion is an arc).
class WheelPathEncoder {
 public:
  explicit WheelPathEncoder(double track_width_m) : track_(track_width_m) {}
  void Reset(const Pose2& pose) {
    last_ = pose;
    started_ = true;
  }
  agilex::WheelDistances Advance(const Pose2& pose);
  double left_m() const { return left_; }
  double right_m() const { return right_; }

 private:
  double track_;
  Pose2 last_;
  bool started_ = false;
  double left_ = 0.0;
  double right_ = 0.0;
};

class FakeAgilexBase {
 public:
  FakeAgilexBase(const FakeAgilexOptions& options, std::shared_ptr<const Recording> recording,
                 std::shared_ptr<const PlaybackClock> clock);
  ~FakeAgilexBase();
  FakeAgilexBase(const FakeAgilexBase&) = delete;
  FakeAgilexBase& operator=(const FakeAgilexBase&) = delete;

  bool Open(std::string* error);  // listens; call before Start()
  void Start();
  void Stop();

  std::string interface_name() const { return "unix:" + options_.socket_path; }
  size_t clients() const { return clients_.load(); }
  bool finished() const { return finished_.load(); }
  uint64_t frames_sent() const { return frames_.load(); }
  const FaultCounts& fault_counts() const { return counts_; }
  // The 0x311 frames sent intact (not truncated, not the jump itself), in order: the last
  // sent_record_capacity of them, and the count of all.
  const SentRecord<SentOdometry>& sent_intact() const { return sent_intact_; }

 private:
  void Loop();
  void SendTick(uint64_t tick, Time log_time, Time now);
  bool Stalled(Time now) const;

  FakeAgilexOptions options_;
  std::shared_ptr<const Recording> recording_;
  std::shared_ptr<const PlaybackClock> clock_;
  FakeCanBus bus_;
  WheelPathEncoder encoder_;
  std::thread thread_;
  std::atomic<bool> stop_{false};
  std::atomic<bool> finished_{false};
  std::atomic<size_t> clients_{0};
  std::atomic<uint64_t> frames_{0};
  FaultCounts counts_;
  int64_t jump_offset_mm_ = 0;
  uint64_t odometry_index_ = 0;
  bool dropped_ = false;
  bool stall_counted_ = false;
  Pose2 previous_pose_;
  SentRecord<SentOdometry> sent_intact_;
};

}  // namespace atlas::fake
