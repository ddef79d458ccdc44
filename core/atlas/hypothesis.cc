#include "core/atlas/hypothesis.h"

#include <algorithm>
#include <cmath>

namespace atlas {

std::string HypothesisQualityOptions::Validate() const {
  if (!(alpha >= 0.0 && alpha <= 1.0)) return "quality.alpha must lie in [0, 1]";
  if (!(sigma_x > 0 && sigma_y > 0 && sigma_theta > 0))
    return "quality.sigma_x, sigma_y, sigma_theta must be positive";
  if (window < 1 || window > 1000) return "quality.window must lie in [1, 1000]";
  if (!(empty_explanation >= 0.0 && empty_explanation <= 1.0))
    return "quality.empty_explanation must lie in [0, 1]";
  return "";
}

double HypothesisQuality(const Mat3& robot_cov, double explanation,
                         const HypothesisQualityOptions& o) {
  const double det_star = std::pow(o.sigma_x * o.sigma_y * o.sigma_theta, 2);
  // A covariance that is not finite (or not positive) carries no certainty; NaN must not
  // pass as a determinant of 0, which would read as fully certain.
  const double det = robot_cov.determinant();
  const double certainty =
      std::isfinite(det) && det >= 0.0 ? std::clamp(1.0 - det / det_star, 0.0, 1.0) : 0.0;
  return o.alpha * certainty + (1.0 - o.alpha) * std::clamp(explanation, 0.0, 1.0);
}

void QualityWindow::Add(const ScanUpdate& u) {
  if (static_cast<int>(ring_.size()) != capacity_) ring_.assign(capacity_, Entry{});
  Entry& slot = ring_[head_];
  if (size_ == capacity_) {
    observations_ -= slot.observations;
    matched_ -= slot.matched;
  } else {
    ++size_;
  }
  slot.observations = std::max(0, u.observations);
  slot.matched = std::clamp(u.matched, 0, slot.observations);
  observations_ += slot.observations;
  matched_ += slot.matched;
  head_ = (head_ + 1) % capacity_;
}

void QualityWindow::Clear() {
  ring_.clear();
  head_ = size_ = observations_ = matched_ = 0;
}

double QualityWindow::Explanation(double empty) const {
  if (observations_ <= 0) return empty;
  return static_cast<double>(matched_) / observations_;
}

void QualityWindow::Restore(int capacity, std::vector<Entry> ring, int head, int size) {
  capacity_ = capacity;
  ring_ = std::move(ring);
  head_ = head;
  size_ = size;
  observations_ = matched_ = 0;
  if (static_cast<int>(ring_.size()) != capacity_) {
    Clear();
    return;
  }
  for (int i = 0; i < size_; ++i) {
    const Entry& e = ring_[(head_ - 1 - i + 2 * capacity_) % capacity_];
    observations_ += e.observations;
    matched_ += e.matched;
  }
}

const char* HypothesisStateName(HypothesisState s) {
  switch (s) {
    case HypothesisState::kJuvenile:
      return "juvenile";
    case HypothesisState::kMature:
      return "mature";
    case HypothesisState::kRetired:
      return "retired";
  }
  return "unknown";
}

std::string LifecycleOptions::Validate() const {
  if (bootstrap_scans < 1) return "lifecycle.bootstrap_scans must be at least 1";
  if (probation_scans < bootstrap_scans + 1)
    return "lifecycle.probation_scans must exceed bootstrap_scans";
  if (!(q_fail >= 0.0 && q_fail <= 1.0)) return "lifecycle.q_fail must lie in [0, 1]";
  if (fail_steps < 1) return "lifecycle.fail_steps must be at least 1";
  if (!(retire_margin >= 0.0 && retire_margin <= 1.0))
    return "lifecycle.retire_margin must lie in [0, 1]";
  if (lag_steps < 1) return "lifecycle.lag_steps must be at least 1";
  if (!(switch_margin >= 0.0 && switch_margin <= 1.0))
    return "lifecycle.switch_margin must lie in [0, 1]";
  return "";
}

JuvenileVerdict JudgeJuvenile(const Hypothesis& h, double best_mature_q, bool bootstrap_failed,
                              const LifecycleOptions& o) {
  if (h.state != HypothesisState::kJuvenile) return JuvenileVerdict::kContinue;
  if (bootstrap_failed) return JuvenileVerdict::kDelete;
  if (h.steps < o.probation_scans) return JuvenileVerdict::kContinue;
  if (!h.bootstrapped) return JuvenileVerdict::kDelete;
  return h.q > best_mature_q ? JuvenileVerdict::kMature : JuvenileVerdict::kDelete;
}

bool UpdateFailing(Hypothesis* h, const LifecycleOptions& o) {
  if (h->state != HypothesisState::kMature) return false;
  h->failing_steps = h->q < o.q_fail ? h->failing_steps + 1 : 0;
  return h->failing_steps >= o.fail_steps;
}

bool UpdateLagging(Hypothesis* h, bool h_is_dominant, double dominant_q,
                   const LifecycleOptions& o) {
  if (h->state != HypothesisState::kMature) return false;
  const bool lagging = !h_is_dominant && h->q < dominant_q - o.retire_margin;
  h->lagging_steps = lagging ? h->lagging_steps + 1 : 0;
  return h->lagging_steps >= o.lag_steps;
}

int DominantIndex(const std::vector<Hypothesis>& hypotheses, double switch_margin) {
  int best = -1, previous = -1;
  for (int i = 0; i < static_cast<int>(hypotheses.size()); ++i) {
    const Hypothesis& h = hypotheses[i];
    if (h.state != HypothesisState::kMature) continue;
    if (h.dominant) previous = i;
    if (best < 0 || h.q > hypotheses[best].q ||
        (h.q == hypotheses[best].q && h.id < hypotheses[best].id))
      best = i;
  }
  if (switch_margin > 0.0 && previous >= 0 &&
      hypotheses[previous].q >= hypotheses[best].q - switch_margin)
    return previous;
  return best;
}

namespace {

class WholeBootstrap final : public BootstrapSearch {
 public:
  WholeBootstrap(const PoseBootstrapper& w, const UncertainPose& seed) : w_(w), seed_(seed) {}
  bool Continue(const LocalMap& map, const LocalMap& frame_map,
                const std::vector<JuvenileScan>& z) override {
    result_ = w_.Solve(map, frame_map, z, seed_);
    return true;
  }
  PoseBootstrap TakeResult() override { return std::move(result_); }

 private:
  const PoseBootstrapper& w_;
  UncertainPose seed_;
  PoseBootstrap result_;
};

}  // namespace

std::unique_ptr<BootstrapSearch> PoseBootstrapper::Begin(const LocalMap&, const LocalMap&,
                                                         const std::vector<JuvenileScan>&,
                                                         const UncertainPose& seed) const {
  return std::make_unique<WholeBootstrap>(*this, seed);
}

}  // namespace atlas
