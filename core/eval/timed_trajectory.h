#pragma once
// A trajectory as poses at time stamps, searchable by stamp. Pure data, no I/O.

#include <optional>
#include <vector>

#include "core/common/time.h"
#include "core/geometry/se2.h"

namespace atlas::eval {

struct TimedPose {
  Time stamp{};
  Pose2 pose;
};

class TimedTrajectory {
 public:
  TimedTrajectory() = default;
  // Sorts by stamp (stable: of equal stamps the first given is found).
  explicit TimedTrajectory(std::vector<TimedPose> poses);

  const std::vector<TimedPose>& poses() const { return poses_; }
  size_t size() const { return poses_.size(); }
  bool empty() const { return poses_.empty(); }

  // Index of the pose whose stamp is nearest to `t`, if it is within `tolerance`.
  std::optional<size_t> IndexAt(Time t, Duration tolerance) const;
  std::optional<Pose2> PoseAt(Time t, Duration tolerance) const;

 private:
  std::vector<TimedPose> poses_;
};

}  // namespace atlas::eval
