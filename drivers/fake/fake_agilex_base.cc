#include "drivers/fake/fake_agilex_base.h"

#include <cmath>

namespace atlas::fake {

std::string FakeAgilexOptions::Validate() const {
  if (socket_path.empty()) return "fake AgileX: socket_path is empty";
  if (track_width_m <= 0) return "fake AgileX: track_width_m must be > 0";
  if (odometry_period_s <= 0) return "fake AgileX: odometry_period_s must be > 0";
  if (system_every < 1) return "fake AgileX: system_every must be >= 1";
  return faults.Validate();
}

agilex::WheelDistances WheelPathEncoder::Advance(const Pose2& pose) {
  if (!started_) Reset(pose);
  const Pose2 d = Between(last_, pose);
  last_ = pose;
  const double dtheta = d.theta;
  const double chord = std::hypot(d.x, d.y);
  double ds = chord;
  if (std::abs(dtheta) > 1e-9) {
    const double half = 0.5 * dtheta;
    ds = chord * half / std::sin(half);
  }
  if (d.x < 0) ds = -ds;
  left_ += ds - 0.5 * dtheta * track_;
  right_ += ds + 0.5 * dtheta * track_;
  return {static_cast<int32_t>(std::llround(left_ * 1000.0)),
          static_cast<int32_t>(std::llround(right_ * 1000.0))};
}

FakeAgilexBase::FakeAgilexBase(const FakeAgilexOptions& options,
                               std::shared_ptr<const Recording> recording,
                               std::shared_ptr<const PlaybackClock> clock)
    : options_(options),
      recording_(std::move(recording)),
      clock_(std::move(clock)),
      encoder_(options.track_width_m),
      sent_intact_(options.sent_record_capacity) {}

FakeAgilexBase::~FakeAgilexBase() { Stop(); }

bool FakeAgilexBase::Open(std::string* error) { return bus_.Listen(options_.socket_path, error); }

void FakeAgilexBase::Start() {
  if (thread_.joinable()) return;
  stop_.store(false);
  thread_ = std::thread([this] { Loop(); });
}

void FakeAgilexBase::Stop() {
  stop_.store(true);
  if (thread_.joinable()) thread_.join();
  bus_.Close();
}

bool FakeAgilexBase::Stalled(Time now) const {
  const FaultOptions& f = options_.faults;
  if (f.stall_after_s < 0 || !clock_->started()) return false;
  const double t = ToSeconds(now - clock_->WallAt(clock_->log_start()));
  return t >= f.stall_after_s && t < f.stall_after_s + f.stall_for_s;
}

void FakeAgilexBase::SendTick(uint64_t tick, Time log_time, Time now) {
  const Pose2 pose = recording_->OdometryAt(log_time);
  const agilex::WheelDistances exact = encoder_.Advance(pose);
  const double dt = options_.odometry_period_s;
  const Pose2 step = Between(previous_pose_, pose);
  previous_pose_ = pose;
  if (Stalled(now)) return;
  const FaultOptions& f = options_.faults;
  ++odometry_index_;
  auto every = [&](int n) { return n > 0 && odometry_index_ % static_cast<uint64_t>(n) == 0; };
  if (every(f.jump_every)) {
    jump_offset_mm_ += f.jump_mm;
    counts_.jumps.fetch_add(1);
  }
  agilex::WheelDistances sent{static_cast<int32_t>(exact.left_mm + jump_offset_mm_),
                              static_cast<int32_t>(exact.right_mm + jump_offset_mm_)};
  if (every(f.garbage_every)) {
    const std::string g = GarbageBytes(f.garbage_bytes % 15 + 1, static_cast<uint32_t>(tick));
    if (bus_.BroadcastRaw(g.data(), g.size()) > 0) counts_.garbage.fetch_add(1);
  }
  CanFrame odo = agilex::EncodeOdometry(sent);
  bool intact = true;
  if (every(f.truncate_every)) {
    odo.dlc = 4;
    intact = false;
    counts_.truncated.fetch_add(1);
  }
  const bool jumped_now = every(f.jump_every);
  if (bus_.Broadcast(odo) > 0) {
    frames_.fetch_add(1);
    if (intact && !jumped_now) sent_intact_.Add({tick, log_time, sent, pose});
  }
  agilex::MotionState m;
  m.linear_mm_s = static_cast<int16_t>(std::clamp(step.x / dt * 1000.0, -32768.0, 32767.0));
  m.angular_mrad_s = static_cast<int16_t>(std::clamp(step.theta / dt * 1000.0, -32768.0, 32767.0));
  if (bus_.Broadcast(agilex::EncodeMotionState(m)) > 0) frames_.fetch_add(1);
  if (tick % static_cast<uint64_t>(options_.system_every) == 0) {
    agilex::SystemState s;
    s.battery_dv = 264;
    s.rolling_count = static_cast<uint8_t>(tick / static_cast<uint64_t>(options_.system_every));
    if (bus_.Broadcast(agilex::EncodeSystemState(s)) > 0) frames_.fetch_add(1);
  }
}

void FakeAgilexBase::Loop() {
  const Duration period(static_cast<int64_t>(options_.odometry_period_s * 1e9));
  uint64_t tick = 0;
  previous_pose_ = recording_->OdometryAt(recording_->begin);
  while (!stop_.load()) {
    clients_.store(bus_.AcceptPending());
    const Time now = Now();
    if (!clock_->started()) {
      std::this_thread::sleep_for(std::chrono::milliseconds(2));
      continue;
    }
    const FaultOptions& f = options_.faults;
    if (f.drop_after_s >= 0 && !dropped_ &&
        ToSeconds(now - clock_->WallAt(clock_->log_start())) >= f.drop_after_s) {
      dropped_ = true;
      bus_.Close();
      counts_.drops.fetch_add(1);
      const Time until = now + Duration(static_cast<int64_t>(f.drop_for_s * 1e9));
      while (!stop_.load() && Now() < until)
        std::this_thread::sleep_for(std::chrono::milliseconds(5));
      std::string error;
      while (!stop_.load() && !bus_.Listen(options_.socket_path, &error))
        std::this_thread::sleep_for(std::chrono::milliseconds(50));
      continue;
    }
    if (Stalled(now) && !stall_counted_) {
      stall_counted_ = true;
      counts_.stalls.fetch_add(1);
    }
    // Catch up on every tick due (the base's counters advance whether or not anyone listens).
    while (true) {
      const Time log_time = clock_->log_start() + period * static_cast<int64_t>(tick);
      if (log_time > recording_->end) {
        finished_.store(true);
        break;
      }
      if (clock_->WallAt(log_time) > Now()) break;
      SendTick(tick, log_time, Now());
      ++tick;
    }
    const Time next = clock_->WallAt(clock_->log_start() + period * static_cast<int64_t>(tick));
    const Duration wait =
        std::clamp<Duration>(next - Now(), Duration::zero(), std::chrono::milliseconds(5));
    std::this_thread::sleep_for(wait);
  }
}

}  // namespace atlas::fake
