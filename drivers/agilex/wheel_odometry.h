#pragma once
// Dead reckoning of a differential-drive base from its cumulative wheel distances (AgileX
// 0x311). Pure: counters and arrival stamps in, an atlas::OdometrySample out.
//
// Each step integrates the change of the two wheel distances dl, dr (metres):
//   ds = (dl + dr) / 2,  dtheta = (dr - dl) / track_width,
// as an arc (exact for constant wheel speeds over the step), composed onto the pose (SE(2)
// composition, paper eq. 2). A change that no robot could drive in the elapsed time,
// |dl| or |dr| > max_speed * dt + slack (base reboot resetting the counters to 0, int32 wrap,
// a corrupted frame), is a discontinuity: reported, not integrated, and integration resumes
// from the new counter values, so the pose never jumps. The limit grows with dt, so a long gap
// would let a counter reset through as motion (a base reboot always comes with a gap of
// seconds): after a gap longer than max_gap_s, and on the first update after Rereference() (the
// reader calls it on every (re)connect), the counters are only taken as the new reference, as
// the very first ones are; this too counts as a discontinuity.

#include <cstdint>
#include <string>

#include "core/common/sensor_types.h"
#include "core/common/time.h"
#include "drivers/agilex/agilex_messages.h"

namespace atlas::agilex {

struct WheelOdometryOptions {
  double track_width_m = 0.58;  // distance between the wheel contact lines (AgileX Scout 2.0)
  double max_speed_mps = 3.0;   // fastest plausible wheel speed
  double slack_m = 0.02;        // allowance for stamp jitter and counter quantisation
  // Longest gap between two 0x311 frames (nominal period 20 ms) across which a change is still
  // integrated; after a longer one the counters are re-referenced (one discontinuity) and the
  // motion across the gap is lost. 1 s: far longer than a loaded machine's delays, far shorter
  // than a base reboot.
  double max_gap_s = 1.0;
  // Empty when valid, else what is wrong.
  std::string Validate() const;
};

enum class OdometryStep {
  kFirst,          // first counters: the reference, pose stays at the origin
  kIntegrated,     // the change was integrated
  kDiscontinuity,  // implausible change: skipped, counters re-referenced
  kRereferenced,   // after a gap or Rereference(): the new reference, pose kept (a discontinuity)
};

// Why the last kDiscontinuity was one.
enum class DiscontinuityCause { kNone, kImplausibleChange, kGap, kRereferenced };
const char* ToString(DiscontinuityCause c);

class WheelOdometryIntegrator {
 public:
  // options must be valid (asserted).
  explicit WheelOdometryIntegrator(const WheelOdometryOptions& options);

  // Feeds one 0x311 frame's counters, stamped at arrival. A change is plausible within
  // max_speed_mps * max(dt, kFramePeriodS) + slack_m: frames that arrive together (or with a
  // stamp that does not increase) still each cover one period of the base's motion.
  OdometryStep Update(Time stamp, const WheelDistances& counters);

  // The cumulative pose at the last update (stamp of the last update).
  const OdometrySample& sample() const { return sample_; }
  uint64_t discontinuities() const { return discontinuities_; }
  uint64_t updates() const { return updates_; }
  DiscontinuityCause last_cause() const { return last_cause_; }
  // Forgets the counters but keeps the pose: the next Update only takes its counters as the new
  // reference. It is kRereferenced, a counted discontinuity, when there was a reference (the
  // motion across it is lost), kFirst otherwise.
  void Rereference() { rereference_ = have_reference_; }

 private:
  WheelOdometryOptions options_;
  OdometrySample sample_;
  WheelDistances last_{};
  Time last_stamp_{};
  bool have_reference_ = false;
  bool rereference_ = false;
  DiscontinuityCause last_cause_ = DiscontinuityCause::kNone;
  uint64_t discontinuities_ = 0;
  uint64_t updates_ = 0;
};

}  // namespace atlas::agilex
