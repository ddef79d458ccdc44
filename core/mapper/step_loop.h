#pragma once
// The step loop's logic, without threads or devices, so that the live daemon and the offline
// replay run the same code (docs/atlasd.md, "Threads and the loop" and "Offline replay").
//
// Contract:
// - AddOdometry / AddScan / Pending never block and never allocate beyond fixed capacities
//   (scans are moved in; the pending ring holds `max_pending_scans`).
// - When more than `max_pending_scans` scans wait, the OLDEST is dropped and counted
//   (dropped_scans): the loop never queues work up when it falls behind.
// - StepOne() steps the atlas with the oldest pending scan: the odometry increment is the
//   difference of the odometry poses at the previous and the current scan's time taken (for a
//   scan: its stamp + laser_time_offset, below; for a sonar reading: its stamp), each
//   interpolated between the samples bracketing the stamp (OdometryTrack; extrapolated briefly
//   when the scan is newer than every sample), using only the odometry that had arrived when
//   the scan was added, so that a scan stepped late gives the same result as one stepped at
//   once (live and replay agree).
// - Per-scan preprocessing is the loop's: when a scan is added its stamp is truncated to
//   `stamp_resolution` (below) and its ranges at or beyond its own max_range (the scanner's
//   maximum as its source states it; none when not positive) become kNoReturn
//   (LimitLaserRange). A device's range setting is applied by its source (the driver, the LCM
//   input), so the maps use the ranges the scanner gives. When a scan is stepped, the odometry
//   is looked up at the time it was taken (stamp + laser_time_offset, below). Odometry samples
//   and sonar readings have their stamps truncated the same way when added.
// - Stamp resolution: the stamps of everything added are truncated to a whole multiple of
//   `stamp_resolution` (zero: kept as given). The live daemon sets the resolution at which its
//   recording of the raw inputs keeps stamps (the raw LCM channels: whole microseconds), so
//   that a replay of that recording steps exactly the stamps the live loop stepped; the replay
//   of a log keeps the log's stamps (zero).
//   The step time is measured; a step longer than step_budget is an overrun (counted).
//   The pose is reported to the sink (OnPose) as soon as the atlas has localised
//   (Atlas::Localize), before map-matching and edge refinement (Atlas::MaintainGraph), so that
//   the pose latency does not carry the graph work; OnStep follows the whole step, and the
//   step time covers both halves.
// - Dead reckoning: when the newest odometry is more than `laser_timeout` (data time) past the
//   last stepped scan, the laser is considered away: every `dead_reckoning_period` of odometry
//   the sink gets the last dominant pose moved by the odometry since that scan, with covariance
//   grown by the maps' odometry noise model, and laser_silent() is true until a scan is stepped.
// - Sonar (localmap.sensors "sonar" or "both"): AddSonar() queues ring readings in a second
//   ring of `max_pending_scans` (oldest dropped and counted, dropped_sonar); StepOne() steps
//   the pending item of either ring that was ADDED first, a reading with Atlas::Localize(delta,
//   reading), with the odometry increment taken as for a scan (backwards when it is older than
//   the item stepped before it). A stepped reading counts as a range step for the
//   laser-silence rule (with sonar alone there is no laser to wait for). The caller adds only
//   the kinds its maps use, in stamp order as far as it knows them (the live loop merges each
//   drain of the two queues by stamp). The order of the Add calls, not the stamps, is the step
//   order, so that a replay adding the items in the order a recording holds them steps them
//   as live did, however the live steps fell between arrivals (a scan whose reader was
//   preempted between its arrival stamp and its push comes after a newer reading; live and
//   replay both step it after the reading).
// - Laser time offset: a scan was TAKEN at stamp + laser_time_offset (negative: before its
//   stamp). Drivers stamp a scan at the arrival of the telegram's last byte (laser_reader.h),
//   but the mirror swept the beams before the scanner sent the telegram, and the serial line
//   takes time: a 361-value SICK LMS telegram (732 bytes, 10 bits a byte) takes about 0.19 s at
//   38400 baud and about 15 ms at 500 kbaud (a 181-value one half as long), plus the sweep
//   itself. On mit-csail (361 beams at 4.7 Hz, the rate 38400 baud allows: docs/devices.md)
//   the odometry fits best 0.10-0.12 s before the stamps (docs/design.md, "Laser time offset";
//   replay/laser_time_offset.h calibrates the offset without ground truth). Only the
//   odometry lookup uses the offset: the scan's stamp stays its identity (the stamp of the
//   pose reported to the sink, of last_scan_stamp(), of the laser-silence rule), as the
//   drivers made it. A positive offset may reach past the odometry known at the scan's
//   arrival; the lookup then extrapolates briefly as above. Sonar readings are looked up at
//   their stamps.
// - Scan matching (MapperSettings::scan_match.enabled): a scan stepped right after another scan
//   is matched against it (core/scanmatch/scan_matcher.h) with the odometry increment and its
//   noise (OdometryIncrementNoise) as the prior; when the match succeeds the atlas predicts
//   with the matched increment and its covariance (Atlas::Localize(UncertainPose, scan)),
//   otherwise with the odometry as without matching (counted: scan_match_fallbacks). A sonar
//   step in between drops the reference (the increment would span two sensors' steps).
// - Deterministic: given the same calls in the same order, the same outputs (replay relies on
//   it; when the steps are made does not matter, only the order of the calls); only the
//   measured step times differ.

#include <cstdint>
#include <functional>
#include <memory>
#include <vector>

#include "core/atlas/atlas.h"
#include "core/mapper/mapper_factory.h"
#include "core/mapper/odometry_track.h"

namespace atlas {

struct StepLoopOptions {
  Duration step_budget = std::chrono::milliseconds(10);
  int max_pending_scans = 2;
  Duration laser_timeout = std::chrono::milliseconds(500);
  Duration dead_reckoning_period = std::chrono::milliseconds(50);
  size_t odometry_capacity = 512;
  // A scan was taken at its stamp + laser_time_offset (contract above); within +-1 s.
  Duration laser_time_offset = Duration::zero();
  // Stamps added are truncated to a multiple of this (contract above); 0 to 1 s, 0: kept.
  Duration stamp_resolution = Duration::zero();
  std::string Validate() const;
  bool operator==(const StepLoopOptions&) const = default;
};

enum class PoseSource { kScan, kOdometryOnly };

// What the loop reports; implemented by the LCM publisher and by the replay writer.
class StepSink {
 public:
  virtual ~StepSink() = default;
  // After every step (source kScan) and while dead reckoning (kOdometryOnly).
  virtual void OnPose(Time stamp, const DominantOutput& pose, PoseSource source) = 0;
  // After every step, with the atlas (for the periodic graph, map and hypothesis output).
  virtual void OnStep(Time stamp, const Atlas& atlas) = 0;
};

// Step times since the last TakePeriod(), in microseconds (bounded sample).
struct StepTimeSummary {
  int steps = 0;
  float min_us = 0, median_us = 0, p99_us = 0, max_us = 0;
};

class StepLoop {
 public:
  // `atlas` is owned by the caller and outlives the loop; settings as used to make it.
  StepLoop(const StepLoopOptions& options, const MapperSettings& settings, Atlas* atlas);

  void AddOdometry(const OdometrySample& sample);
  void AddScan(LaserScan&& scan);
  void AddSonar(SonarReading&& reading);
  size_t Pending() const { return pending_size_ + sonar_size_; }
  // Steps the pending scan or sonar reading added first; false when none is pending.
  bool StepOne(StepSink* sink);
  // Steps every pending scan.
  int StepAll(StepSink* sink);

  // Options that a reload may change (step budget, periods); capacities stay.
  void SetStepBudget(Duration budget) { options_.step_budget = budget; }
  // A reload with new atlas parameters: the loop goes on with `atlas` (the old one rebuilt
  // with the new settings, see reload.h); odometry and pending scans are kept.
  void ReplaceAtlas(Atlas* atlas, const MapperSettings& settings) {
    atlas_ = atlas;
    settings_ = settings;
    matcher_ = ScanMatcher(settings.scan_match);
  }

  int64_t steps() const { return steps_; }
  int64_t overruns() const { return overruns_; }
  int64_t dropped_scans() const { return dropped_scans_; }
  int64_t dropped_sonar() const { return dropped_sonar_; }
  int64_t scans_without_odometry() const { return scans_without_odometry_; }
  int64_t scan_matches() const { return scan_matches_; }
  int64_t scan_match_fallbacks() const { return scan_match_fallbacks_; }
  bool laser_silent() const { return laser_silent_; }
  // The pose last reported to the sink: the dominant one after a step, moved by the odometry
  // while the laser is away (what ATLAS_POSE carries; the health line shows it too).
  const DominantOutput& published_pose() const { return dead_reckoned_; }
  Time last_scan_stamp() const { return last_scan_stamp_; }
  const Atlas& atlas() const { return *atlas_; }
  StepTimeSummary TakePeriod();

 private:
  void DeadReckon(StepSink* sink);
  // The preprocessing of a scan when it is added (contract above).
  void PrepareScan(LaserScan* scan) const;
  // Atlas::Localize with the odometry increment, or with the scan-matched one (above).
  void LocalizeWithScan(const Pose2& delta, const LaserScan& scan);

  StepLoopOptions options_;
  MapperSettings settings_;
  Atlas* atlas_;
  OdometryTrack track_;
  std::vector<LaserScan> pending_;          // ring
  std::vector<uint64_t> pending_odometry_;  // odometry samples known at each scan's arrival
  std::vector<uint64_t> pending_order_;     // the Add call's number, for the step order
  size_t pending_head_ = 0, pending_size_ = 0;
  std::vector<SonarReading> sonar_;  // ring, like pending_
  std::vector<uint64_t> sonar_odometry_, sonar_order_;
  uint64_t added_ = 0;  // scans and readings added
  size_t sonar_head_ = 0, sonar_size_ = 0;
  int64_t dropped_sonar_ = 0;
  bool have_previous_ = false;
  Pose2 previous_odometry_;
  Time last_scan_stamp_{};
  DominantOutput last_dominant_;
  bool laser_silent_ = false;
  Time last_dead_reckoning_{};
  // The published pose while the laser is away, and the odometry it was last moved to: each
  // dead-reckoning period composes one increment, so the covariance grows with the path.
  DominantOutput dead_reckoned_;
  Pose2 dead_reckoned_odometry_;
  int64_t steps_ = 0, overruns_ = 0, dropped_scans_ = 0, scans_without_odometry_ = 0;
  ScanMatcher matcher_;
  int64_t scan_matches_ = 0, scan_match_fallbacks_ = 0;
  std::vector<float> period_us_, scratch_us_;
  size_t period_count_ = 0;
  float period_min_ = 0, period_max_ = 0;
};

// The readings and scans drained together, in stamp order (a scan before a reading of the same
// stamp): calls on_reading(SonarReading&) and on_scan(LaserScan&) one item at a time, so that
// the caller adds (and republishes) them in that order. Each vector must be in stamp order.
template <typename OnReading, typename OnScan>
void InStampOrder(std::vector<SonarReading>& readings, std::vector<LaserScan>& scans,
                  OnReading&& on_reading, OnScan&& on_scan) {
  size_t i = 0, j = 0;
  while (i < readings.size() || j < scans.size()) {
    if (j == scans.size() || (i < readings.size() && readings[i].stamp < scans[j].stamp)) {
      on_reading(readings[i++]);
    } else {
      on_scan(scans[j++]);
    }
  }
}

}  // namespace atlas
