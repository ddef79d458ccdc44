#include "core/mapper/step_loop.h"

#include <algorithm>

namespace atlas {
namespace {
constexpr size_t kPeriodSample = 2048;

// Appends to a fixed ring (head, size), dropping and counting the oldest when full; returns the
// slot written.
template <typename T>
size_t PushDroppingOldest(std::vector<T>& ring, size_t& head, size_t& size, int64_t& dropped,
                          T&& item) {
  if (size == ring.size()) {
    head = (head + 1) % ring.size();
    --size;
    ++dropped;
  }
  const size_t slot = (head + size) % ring.size();
  ring[slot] = std::move(item);
  ++size;
  return slot;
}
}  // namespace

std::string StepLoopOptions::Validate() const {
  if (step_budget <= Duration::zero()) return "step budget must be positive";
  if (max_pending_scans < 1) return "max_pending_scans must be at least 1";
  if (laser_timeout <= Duration::zero()) return "laser_timeout must be positive";
  if (odometry_capacity < 2) return "odometry_capacity must be at least 2";
  if (laser_time_offset < -std::chrono::seconds(1) || laser_time_offset > std::chrono::seconds(1))
    return "laser_time_offset must be within -1 s and +1 s";
  if (stamp_resolution < Duration::zero() || stamp_resolution > std::chrono::seconds(1))
    return "stamp_resolution must be within 0 and 1 s";
  return "";
}

StepLoop::StepLoop(const StepLoopOptions& options, const MapperSettings& settings, Atlas* atlas)
    : options_(options),
      settings_(settings),
      atlas_(atlas),
      track_(options.odometry_capacity),
      pending_(static_cast<size_t>(options.max_pending_scans)),
      pending_odometry_(static_cast<size_t>(options.max_pending_scans)),
      pending_order_(static_cast<size_t>(options.max_pending_scans)),
      sonar_(static_cast<size_t>(options.max_pending_scans)),
      sonar_odometry_(static_cast<size_t>(options.max_pending_scans)),
      sonar_order_(static_cast<size_t>(options.max_pending_scans)),
      matcher_(settings.scan_match) {
  period_us_.reserve(kPeriodSample);
  scratch_us_.reserve(kPeriodSample);
}

void StepLoop::AddOdometry(const OdometrySample& added) {
  OdometrySample sample = added;
  sample.stamp = Truncate(sample.stamp, options_.stamp_resolution);
  if (track_.empty() && !have_previous_) {
    // No scan yet: dead reckoning (if the laser never comes) starts at the first odometry.
    previous_odometry_ = sample.pose;
    last_scan_stamp_ = sample.stamp;
  }
  track_.Add(sample);
  if (track_.Newest().stamp - last_scan_stamp_ > options_.laser_timeout && Pending() == 0)
    laser_silent_ = true;
}

void StepLoop::PrepareScan(LaserScan* scan) const {
  scan->stamp = Truncate(scan->stamp, options_.stamp_resolution);
  if (scan->max_range > 0.0f) LimitLaserRange(scan, scan->max_range);
}

void StepLoop::AddScan(LaserScan&& scan) {
  PrepareScan(&scan);
  const size_t slot =
      PushDroppingOldest(pending_, pending_head_, pending_size_, dropped_scans_, std::move(scan));
  pending_odometry_[slot] = track_.added();
  pending_order_[slot] = added_++;
}

void StepLoop::AddSonar(SonarReading&& reading) {
  reading.stamp = Truncate(reading.stamp, options_.stamp_resolution);
  const size_t slot =
      PushDroppingOldest(sonar_, sonar_head_, sonar_size_, dropped_sonar_, std::move(reading));
  sonar_odometry_[slot] = track_.added();
  sonar_order_[slot] = added_++;
}

bool StepLoop::StepOne(StepSink* sink) {
  if (pending_size_ == 0 && sonar_size_ == 0) {
    if (laser_silent_) DeadReckon(sink);
    return false;
  }
  const bool sonar = sonar_size_ > 0 && (pending_size_ == 0 ||
                                         sonar_order_[sonar_head_] < pending_order_[pending_head_]);
  LaserScan& scan = pending_[pending_head_];
  const Time stamp = sonar ? sonar_[sonar_head_].stamp : scan.stamp;
  Pose2 odometry;
  const Time taken = sonar ? stamp : stamp + options_.laser_time_offset;
  const OdometryLookup lookup = track_.PoseAt(
      taken, sonar ? sonar_odometry_[sonar_head_] : pending_odometry_[pending_head_], &odometry);
  if (lookup == OdometryLookup::kNoData) {
    ++scans_without_odometry_;
    odometry = have_previous_ ? previous_odometry_ : Pose2{};
  }
  const Pose2 delta = have_previous_ ? Between(previous_odometry_, odometry) : Pose2{};
  if (!have_previous_) laser_silent_ = false;

  const auto t0 = std::chrono::steady_clock::now();
  if (sonar) {
    atlas_->Localize(delta, sonar_[sonar_head_]);
    sonar_head_ = (sonar_head_ + 1) % sonar_.size();
    --sonar_size_;
    matcher_.ClearReference();
  } else {
    LocalizeWithScan(delta, scan);
    pending_head_ = (pending_head_ + 1) % pending_.size();
    --pending_size_;
  }
  have_previous_ = true;
  previous_odometry_ = odometry;
  last_scan_stamp_ = stamp;
  laser_silent_ = false;
  last_dominant_ = atlas_->Dominant();
  dead_reckoned_ = last_dominant_;
  dead_reckoned_odometry_ = odometry;
  sink->OnPose(stamp, last_dominant_, PoseSource::kScan);
  atlas_->MaintainGraph();
  const auto elapsed = std::chrono::steady_clock::now() - t0;

  ++steps_;
  if (elapsed > options_.step_budget) ++overruns_;
  const float us = static_cast<float>(std::chrono::duration<double, std::micro>(elapsed).count());
  if (period_count_ == 0) period_min_ = period_max_ = us;
  period_min_ = std::min(period_min_, us);
  period_max_ = std::max(period_max_, us);
  if (period_us_.size() < kPeriodSample) period_us_.push_back(us);
  ++period_count_;
  sink->OnStep(stamp, *atlas_);
  return true;
}

void StepLoop::LocalizeWithScan(const Pose2& delta, const LaserScan& scan) {
  if (!settings_.scan_match.enabled) {
    atlas_->Localize(delta, scan);
    return;
  }
  bool matched = false;
  if (have_previous_ && matcher_.HasReference()) {
    const ScanMatchResult m =
        matcher_.Match(scan, UncertainPose{delta, OdometryIncrementNoise(delta, settings_)});
    matched = m.outcome == ScanMatchOutcome::kMatched;
    if (matched) {
      ++scan_matches_;
      atlas_->Localize(m.increment, scan);
    } else {
      ++scan_match_fallbacks_;
    }
  }
  if (!matched) atlas_->Localize(delta, scan);
  matcher_.SetReference(scan);
}

int StepLoop::StepAll(StepSink* sink) {
  int n = 0;
  while (StepOne(sink)) ++n;
  return n;
}

void StepLoop::DeadReckon(StepSink* sink) {
  if (track_.empty()) return;
  const OdometrySample& newest = track_.Newest();
  if (newest.stamp - last_dead_reckoning_ < options_.dead_reckoning_period) return;
  last_dead_reckoning_ = newest.stamp;
  const Pose2 delta = Between(dead_reckoned_odometry_, newest.pose);
  const UncertainPose increment{delta, OdometryIncrementNoise(delta, settings_)};
  dead_reckoned_.pose = Compose(dead_reckoned_.pose, increment);
  dead_reckoned_.switched = false;  // motion since the last step, not a switch
  dead_reckoned_odometry_ = newest.pose;
  sink->OnPose(newest.stamp, dead_reckoned_, PoseSource::kOdometryOnly);
}

StepTimeSummary StepLoop::TakePeriod() {
  StepTimeSummary s;
  s.steps = static_cast<int>(period_count_);
  if (period_count_ > 0) {
    scratch_us_.assign(period_us_.begin(), period_us_.end());
    const size_t n = scratch_us_.size();
    std::nth_element(scratch_us_.begin(), scratch_us_.begin() + n / 2, scratch_us_.end());
    s.median_us = scratch_us_[n / 2];
    const size_t k = std::min(n - 1, static_cast<size_t>(0.99 * static_cast<double>(n)));
    std::nth_element(scratch_us_.begin(), scratch_us_.begin() + k, scratch_us_.end());
    s.p99_us = scratch_us_[k];
    s.min_us = period_min_;
    s.max_us = period_max_;
  }
  period_us_.clear();
  period_count_ = 0;
  return s;
}

}  // namespace atlas
