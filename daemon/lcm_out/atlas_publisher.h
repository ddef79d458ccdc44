#pragma once
// Sends atlasd's outputs on the configured LCM channels (lcm.channels.*). Thin: every message
// is made by lcm_convert.h (its utime on the monotonic clock); this class knows the channel
// names and turns each message's utime into microseconds since the epoch as it sends it
// (epoch_clock.h), the one place where the clocks meet. Not thread-safe: one thread (the loop)
// publishes. A failed publish (e.g. no route) is counted, never fatal.

#include <lcm/lcm-cpp.hpp>

#include "atlasd/health_t.hpp"
#include "daemon/lcm_out/epoch_clock.h"
#include "daemon/lcm_out/lcm_convert.h"
#include "formats/config/daemon_options.h"

namespace atlas {

class AtlasPublisher {
 public:
  // `epoch`: EpochClock::Capture() at start in atlasd.
  AtlasPublisher(lcm::LCM* lcm, const LcmChannels& channels, const EpochClock& epoch)
      : lcm_(lcm), channels_(channels), epoch_(epoch) {}

  void Pose(Time stamp, const DominantOutput& d) { Send(channels_.pose, ToPoseMessage(stamp, d)); }
  void ReferencePose(const atlasd::reference_pose_t& m) { Send(channels_.reference_pose, m); }
  void Graph(Time stamp, const Atlas& a) { Send(channels_.graph, ToGraphMessage(stamp, a)); }
  void Hypotheses(Time stamp, const Atlas& a) {
    Send(channels_.hypotheses, ToHypothesesMessage(stamp, a));
  }
  void LocalMap(Time stamp, const Atlas& a) {
    Send(channels_.local_map, ToLocalMapMessage(stamp, a));
  }
  void Health(const atlasd::health_t& h) { Send(channels_.health, h); }
  void RawLaser(const LaserScan& s) { Send(channels_.raw_laser, ToLaserMessage(s)); }
  void RawOdometry(const OdometrySample& s) { Send(channels_.raw_odometry, ToOdometryMessage(s)); }
  void RawSonar(const SonarReading& s) { Send(channels_.raw_sonar, ToSonarMessage(s)); }

  uint64_t failures() const { return failures_; }

 private:
  template <typename M>
  void Send(const std::string& channel, M message) {
    message.utime = epoch_.ToEpoch(message.utime);
    if (lcm_->publish(channel, &message) != 0) ++failures_;
  }

  lcm::LCM* lcm_;
  LcmChannels channels_;
  EpochClock epoch_;
  uint64_t failures_ = 0;
};

}  // namespace atlas
