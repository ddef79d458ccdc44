#include "core/mapper/odometry_track.h"

#include <algorithm>
#include <cassert>

namespace atlas {

OdometryTrack::OdometryTrack(size_t capacity, Duration max_extrapolation)
    : ring_(std::max<size_t>(capacity, 2)), max_extrapolation_(max_extrapolation) {}

const OdometrySample& OdometryTrack::At(size_t i) const {
  return ring_[(head_ + ring_.size() - size_ + i) % ring_.size()];
}

const OdometrySample& OdometryTrack::Newest() const {
  assert(size_ > 0);
  return At(size_ - 1);
}

void OdometryTrack::Add(const OdometrySample& sample) {
  if (size_ > 0 && sample.stamp <= Newest().stamp) {
    ++out_of_order_;
    return;
  }
  ring_[head_] = sample;
  ++added_;
  head_ = (head_ + 1) % ring_.size();
  size_ = std::min(size_ + 1, ring_.size());
}

OdometryLookup OdometryTrack::PoseAt(Time t, uint64_t known, Pose2* pose) const {
  const uint64_t hidden = known >= added_ ? 0 : added_ - known;
  if (hidden >= size_) return OdometryLookup::kNoData;
  const size_t size = size_ - static_cast<size_t>(hidden);
  const OdometrySample& newest = At(size - 1);
  if (t >= newest.stamp) {
    if (size < 2 || t == newest.stamp) {
      *pose = newest.pose;
      return size < 2 && t != newest.stamp ? OdometryLookup::kHeld : OdometryLookup::kInterpolated;
    }
    const OdometrySample& prev = At(size - 2);
    const Time until = std::min(t, newest.stamp + max_extrapolation_);
    const double f = 1.0 + ToSeconds(until - newest.stamp) / ToSeconds(newest.stamp - prev.stamp);
    *pose = InterpolatePose(prev.pose, newest.pose, f);
    return until == t ? OdometryLookup::kExtrapolated : OdometryLookup::kHeld;
  }
  if (t <= At(0).stamp) {
    *pose = At(0).pose;
    return t == At(0).stamp ? OdometryLookup::kInterpolated : OdometryLookup::kBeforeTrack;
  }
  // Binary search for the first sample after t.
  size_t lo = 0, hi = size - 1;  // At(lo) < t < At(hi)
  while (hi - lo > 1) {
    const size_t mid = (lo + hi) / 2;
    (At(mid).stamp <= t ? lo : hi) = mid;
  }
  const OdometrySample& a = At(lo);
  const OdometrySample& b = At(hi);
  *pose = InterpolatePose(a.pose, b.pose, ToSeconds(t - a.stamp) / ToSeconds(b.stamp - a.stamp));
  return OdometryLookup::kInterpolated;
}

}  // namespace atlas
