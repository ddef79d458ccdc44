#pragma once
// The hypothesis quality metric q of eq. 5 (Section III-B):
//
//   q = alpha (1 - det(Sigma_x) / det(Sigma_x*)) + (1 - alpha) eta_a / ||Z||
//
// Sigma_x is the robot pose covariance in the map-frame, det(Sigma_x*) = sx^2 sy^2 st^2 from the
// maximum acceptable sigmas, eta_a the matched and ||Z|| the total recent observations. The
// first term is clamped to [0, 1] (a pose worse than acceptable contributes 0); with no recent
// observation the second term is 0. "Recent" is a fixed window of the last scans.

#include <array>

#include "core/geometry/se2.h"
#include "core/localmap/localmap_options.h"

namespace atlas {

double QualityMetric(const Mat3& robot_cov, int matched, int observations,
                     const QualityOptions& options);

// Observation counts of the last `window` scans (fixed capacity, no allocation).
class RecentObservations {
 public:
  static constexpr int kMaxWindow = 64;
  explicit RecentObservations(int window = 5);
  void Add(int observations, int matched);
  void Clear();
  int Observations() const { return observations_; }
  int Matched() const { return matched_; }
  int Window() const { return window_; }
  int Size() const { return size_; }
  // Entry i (0 = oldest) of the window; for serialisation.
  std::array<int, 2> At(int i) const;

 private:
  int window_;
  std::array<std::array<int, 2>, kMaxWindow> ring_{};
  int head_ = 0;  // next write position
  int size_ = 0;
  int observations_ = 0;
  int matched_ = 0;
};

}  // namespace atlas
