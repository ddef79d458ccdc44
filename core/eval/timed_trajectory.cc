#include "core/eval/timed_trajectory.h"

#include <algorithm>

namespace atlas::eval {

TimedTrajectory::TimedTrajectory(std::vector<TimedPose> poses) : poses_(std::move(poses)) {
  std::stable_sort(poses_.begin(), poses_.end(),
                   [](const TimedPose& a, const TimedPose& b) { return a.stamp < b.stamp; });
}

std::optional<size_t> TimedTrajectory::IndexAt(Time t, Duration tolerance) const {
  const auto it = std::lower_bound(poses_.begin(), poses_.end(), t,
                                   [](const TimedPose& p, Time x) { return p.stamp < x; });
  std::optional<size_t> best;
  Duration best_gap = Duration::max();
  if (it != poses_.end()) {  // the first pose at or after t
    best = static_cast<size_t>(it - poses_.begin());
    best_gap = it->stamp - t;
  }
  if (it != poses_.begin()) {  // the last pose before t, if strictly nearer
    auto prev = std::prev(it);
    if (t - prev->stamp < best_gap) {
      best_gap = t - prev->stamp;
      while (prev != poses_.begin() && std::prev(prev)->stamp == prev->stamp) --prev;
      best = static_cast<size_t>(prev - poses_.begin());
    }
  }
  if (!best || best_gap > tolerance) return std::nullopt;
  return best;
}

std::optional<Pose2> TimedTrajectory::PoseAt(Time t, Duration tolerance) const {
  const std::optional<size_t> i = IndexAt(t, tolerance);
  if (!i) return std::nullopt;
  return poses_[*i].pose;
}

}  // namespace atlas::eval
