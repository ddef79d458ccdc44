#include "drivers/fake/fake_p2os.h"

#include <algorithm>
#include <cmath>

namespace atlas::fake {

std::string FakeP2osOptions::Validate() const {
  if (std::string e = sonar.Validate(); !e.empty()) return "fake P2OS: " + e;
  if (sip_period_s <= 0) return "fake P2OS: sip_period_s must be > 0";
  if (watchdog <= Duration::zero()) return "fake P2OS: watchdog must be > 0";
  return faults.Validate();
}

SonarReading SonarFromScan(const LaserScan& scan, const std::vector<SonarTransducer>& ring) {
  SonarReading out;
  out.stamp = scan.stamp;
  for (size_t t = 0; t < ring.size(); ++t) {
    const SonarTransducer& s = ring[t];
    float best = kNoReturn;
    for (size_t i = 0; i < scan.ranges.size(); ++i) {
      const double bearing = scan.angle_min + static_cast<double>(i) * scan.angle_increment;
      if (std::abs(WrapAngle(bearing - s.pose.theta)) > 0.5 * s.beam_width) continue;
      const float r = scan.ranges[i];
      if (IsReturn(r) && r < best) best = r;
    }
    if (IsReturn(best) && best >= s.max_range) best = kNoReturn;
    out.returns.push_back({static_cast<int>(t), best});
  }
  return out;
}

FakeP2os::FakeP2os(const FakeP2osOptions& options, std::shared_ptr<const Recording> recording,
                   std::shared_ptr<const PlaybackClock> clock)
    : FakeSerialDevice("fake P2OS", options.link, options.faults, std::move(clock)),
      options_(options),
      recording_(std::move(recording)),
      sent_intact_(options.sent_record_capacity),
      pulse_times_(options.sent_record_capacity) {}

FakeP2os::~FakeP2os() { Stop(); }

void FakeP2os::OnPowerUp() {
  state_.store(State::kWaitSync0);
  sonar_on_ = false;
  host_decoder_.Reset();
}

void FakeP2os::OnHostBytes(std::span<const uint8_t> bytes, Time now) {
  if (SlaveBaud() != options_.baud) {
    host_decoder_.Reset();
    return;
  }
  host_decoder_.FeedAll(bytes, [&](const p2os::PacketView& p) {
    const auto c = p2os::DecodeHostCommand(p);
    if (!c) return;
    last_command_ = now;
    const State s = state_.load();
    if (s == State::kWaitSync0 && c->command == p2os::kCmdSync0 && !c->argument) {
      SendReply(p2os::EncodeSyncReply(0));
      state_.store(State::kWaitSync1);
    } else if (s == State::kWaitSync1 && c->command == p2os::kCmdSync1 && !c->argument) {
      SendReply(p2os::EncodeSyncReply(1));
      state_.store(State::kWaitSync2);
    } else if (s == State::kWaitSync2 && c->command == p2os::kCmdSync2 && !c->argument) {
      SendReply(p2os::EncodeSync2Reply(options_.identity));
      state_.store(State::kReady);
    } else if (s == State::kReady && c->command == p2os::kCmdOpen) {
      state_.store(State::kOpen);
      next_sip_log_ = clock().started() ? clock().LogAt(now) : recording_->begin;
    } else if (s == State::kOpen || s == State::kReady) {
      if (c->command == p2os::kCmdPulse) {
        pulse_times_.Add(now);
      } else if (c->command == p2os::kCmdClose) {
        state_.store(State::kWaitSync0);
        sonar_on_ = false;
      } else if (c->command == p2os::kCmdSonar) {
        sonar_on_ = c->argument.value_or(0) != 0;
      }
    } else {
      state_.store(State::kWaitSync0);  // out of sequence: start over
    }
  });
}

Time FakeP2os::Tick(Time now) {
  if (clock().LogAt(now) > recording_->end) SetFinished();
  if (state_.load() != State::kOpen) return now + std::chrono::milliseconds(20);
  if (now - last_command_ > options_.watchdog) {
    state_.store(State::kWaitSync0);
    sonar_on_ = false;
    watchdog_closes_.fetch_add(1);
    return now + std::chrono::milliseconds(20);
  }
  const Duration period(static_cast<int64_t>(options_.sip_period_s * 1e9));
  if (next_sip_log_ < recording_->begin) next_sip_log_ = recording_->begin;
  const auto& scans = recording_->scans;
  while (clock().WallAt(next_sip_log_) <= now) {
    const Time t = next_sip_log_;
    next_sip_log_ += period;
    if (t > recording_->end) {
      SetFinished();
      return now + std::chrono::milliseconds(20);
    }
    if (clock().WallAt(next_sip_log_) <= now) continue;  // late: skip to the newest SIP
    p2os::StandardSip sip;
    sip.timer = timer_++;
    SonarReading reading;
    if (sonar_on_) {
      auto it = std::upper_bound(scans.begin(), scans.end(), t,
                                 [](Time v, const LaserScan& s) { return v < s.stamp; });
      if (it != scans.begin()) {
        reading = SonarFromScan(*(it - 1), options_.sonar.ring);
        sip.sonars = p2os::ToSonarRaw(reading, options_.sonar);
      }
    }
    auto packet = p2os::EncodeStandardSip(sip);
    if (packet && SendMessage(std::move(*packet)) && !reading.returns.empty())
      sent_intact_.Add(std::move(reading));
  }
  return clock().WallAt(next_sip_log_);
}

}  // namespace atlas::fake
