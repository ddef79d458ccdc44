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
// from the new counter values, so the pose never jumps.

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
  // Empty when valid, else what is wrong.
  std::string Validate() const;
};

enum class OdometryStep {
  kFirst,          // first counters: the reference, pose stays at the origin
  kIntegrated,     // the change was integrated
  kDiscontinuity,  // implausible change: skipped, counters re-referenced
};

class WheelOdometryIntegrator {
 public:
  // options must be valid (asserted).
  explicit WheelOdometryIntegrator(const WheelOdometryOptions& options);

  // Feeds one 0x311 frame's counters, stamped at arrival. Stamps should increase; a stamp that
  // does not is treated as dt = 0 (only changes within the slack are plausible).
  OdometryStep Update(Time stamp, const WheelDistances& counters);

  // The cumulative pose at the last update (stamp of the last update).
  const OdometrySample& sample() const { return sample_; }
  uint64_t discontinuities() const { return discontinuities_; }
  uint64_t updates() const { return updates_; }
  // Forgets the counters (the next Update is kFirst) but keeps the pose.
  void Rereference() { have_reference_ = false; }

 private:
  WheelOdometryOptions options_;
  OdometrySample sample_;
  WheelDistances last_{};
  Time last_stamp_{};
  bool have_reference_ = false;
  uint64_t discontinuities_ = 0;
  uint64_t updates_ = 0;
};

}  // namespace atlas::agilex
