#include "core/localmap/quality.h"

#include <Eigen/LU>
#include <algorithm>

namespace atlas {

double QualityMetric(const Mat3& robot_cov, int matched, int observations,
                     const QualityOptions& options) {
  const double det_max = options.max_sigma_x * options.max_sigma_x * options.max_sigma_y *
                         options.max_sigma_y * options.max_sigma_theta * options.max_sigma_theta;
  const double det = robot_cov.determinant();
  const double pose_term = std::isfinite(det) ? std::clamp(1.0 - det / det_max, 0.0, 1.0) : 0.0;
  const double match_term =
      observations > 0 ? std::clamp(static_cast<double>(matched) / observations, 0.0, 1.0) : 0.0;
  return options.alpha * pose_term + (1.0 - options.alpha) * match_term;
}

RecentObservations::RecentObservations(int window) : window_(std::clamp(window, 1, kMaxWindow)) {}

void RecentObservations::Add(int observations, int matched) {
  if (size_ == window_) {
    const int oldest = (head_ - size_ + kMaxWindow) % kMaxWindow;
    observations_ -= ring_[oldest][0];
    matched_ -= ring_[oldest][1];
    --size_;
  }
  ring_[head_] = {observations, matched};
  head_ = (head_ + 1) % kMaxWindow;
  ++size_;
  observations_ += observations;
  matched_ += matched;
}

void RecentObservations::Clear() { head_ = size_ = observations_ = matched_ = 0; }

std::array<int, 2> RecentObservations::At(int i) const {
  return ring_[(head_ - size_ + i + 2 * kMaxWindow) % kMaxWindow];
}

}  // namespace atlas
