#pragma once
// The recent odometry samples, for integrating odometry up to a scan's stamp (docs/design.md,
// "The step loop and the daemon").
//
// Contract:
// - Fixed capacity: the oldest samples are overwritten; no allocation after construction.
// - Samples are expected in stamp order; a sample older than the newest one is ignored
//   (counted), so a reordered or duplicated sample never bends the track.
// - PoseAt(t): linear interpolation between the two samples bracketing t (heading along the
//   shorter arc); after the newest sample, constant-velocity extrapolation from the last two
//   samples, at most `max_extrapolation` past the newest (held beyond), so the loop never waits
//   for odometry; before the oldest kept sample, the oldest pose.

#include <cstdint>
#include <vector>

#include "core/common/sensor_types.h"

namespace atlas {

enum class OdometryLookup { kInterpolated, kExtrapolated, kHeld, kBeforeTrack, kNoData };

class OdometryTrack {
 public:
  explicit OdometryTrack(size_t capacity = 256,
                         Duration max_extrapolation = std::chrono::milliseconds(100));

  void Add(const OdometrySample& sample);
  OdometryLookup PoseAt(Time t, Pose2* pose) const { return PoseAt(t, added_, pose); }
  // The same, seeing only the first `known` samples ever added (samples added later are
  // ignored): the loop passes the count at a scan's arrival, so that the result does not depend
  // on how late the scan is stepped (live and replay then agree exactly).
  OdometryLookup PoseAt(Time t, uint64_t known, Pose2* pose) const;
  uint64_t added() const { return added_; }

  bool empty() const { return size_ == 0; }
  const OdometrySample& Newest() const;  // not empty
  uint64_t out_of_order() const { return out_of_order_; }

 private:
  const OdometrySample& At(size_t i) const;  // 0 = oldest

  std::vector<OdometrySample> ring_;
  size_t head_ = 0;  // next write
  size_t size_ = 0;
  Duration max_extrapolation_;
  uint64_t out_of_order_ = 0;
  uint64_t added_ = 0;  // samples accepted so far
};

}  // namespace atlas
