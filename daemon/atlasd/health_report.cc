#include "daemon/atlasd/health_report.h"

#include <unistd.h>

#include <cstdio>

#include "core/common/version.h"
#include "daemon/lcm_out/lcm_convert.h"

namespace atlas {

int64_t ResidentMemoryBytes() {
  FILE* f = std::fopen("/proc/self/statm", "r");
  if (f == nullptr) return 0;
  long long size = 0, resident = 0;
  const int n = std::fscanf(f, "%lld %lld", &size, &resident);
  std::fclose(f);
  return n == 2 ? resident * static_cast<int64_t>(sysconf(_SC_PAGESIZE)) : 0;
}

atlasd::health_t MakeHealthMessage(const HealthInputs& in) {
  atlasd::health_t h{};
  const StepLoop& loop = *in.loop;
  const Atlas& atlas = loop.atlas();
  h.utime = ToUtime(in.now);
  h.uptime_us = ToUtime(Time(in.now - in.start));
  h.steps = loop.steps();
  h.period_steps = in.period.steps;
  h.step_time_min_us = in.period.min_us;
  h.step_time_median_us = in.period.median_us;
  h.step_time_p99_us = in.period.p99_us;
  h.step_time_max_us = in.period.max_us;
  h.step_budget_us = static_cast<float>(in.step_budget_ms * 1000.0);
  h.overruns = loop.overruns();
  h.dropped_scans = loop.dropped_scans();
  h.scan_matches = loop.scan_matches();
  h.scan_match_fallbacks = loop.scan_match_fallbacks();
  for (const DriverEntry& d : in.drivers)
    h.drivers.push_back(ToDriverHealthMessage(d.name, d.health, d.queue_depth, d.queue_capacity));
  h.num_drivers = static_cast<int32_t>(h.drivers.size());
  h.num_frames = atlas.Graph().FrameCount();
  h.num_edges = atlas.Graph().EdgeCount();
  for (const Hypothesis& hy : atlas.Hypotheses()) {
    if (hy.state == HypothesisState::kJuvenile) ++h.num_juvenile;
    if (hy.state == HypothesisState::kMature) ++h.num_mature;
    if (hy.state == HypothesisState::kRetired) ++h.num_retired;
  }
  const DominantOutput d = atlas.Dominant();
  h.dominant_frame_id = d.valid ? d.frame : -1;
  h.store_batches_saved = in.store_saved;
  h.store_batches_dropped = in.store_dropped;
  h.store_errors = in.store_errors;
  h.resident_memory_bytes = ResidentMemoryBytes();

  char buf[512];
  int n = std::snprintf(buf, sizeof(buf),
                        "up %.0fs steps %lld step med %.2f p99 %.2f ms overruns %lld dropped %lld "
                        "frames %d hyps %d/%d",
                        ToSeconds(in.now - in.start), static_cast<long long>(h.steps),
                        h.step_time_median_us / 1000.0, h.step_time_p99_us / 1000.0,
                        static_cast<long long>(h.overruns), static_cast<long long>(h.dropped_scans),
                        h.num_frames, h.num_mature, h.num_juvenile);
  std::string status(buf, std::min<size_t>(static_cast<size_t>(std::max(n, 0)), sizeof(buf) - 1));
  for (const DriverEntry& e : in.drivers) {
    status += " | " + e.name + " " + ToString(e.health.state);
    if (e.health.state == DriverState::kRunning) {
      std::snprintf(buf, sizeof(buf), " %.0fHz", e.health.message_rate_hz);
      status += buf;
    }
    const uint64_t bad = e.health.bad_crc + e.health.bad_length + e.health.bad_messages +
                         e.health.truncated + e.health.discontinuities;
    if (bad > 0 || e.health.garbage_bytes > 0) {
      std::snprintf(buf, sizeof(buf), " (bad %llu, garbage %lluB)",
                    static_cast<unsigned long long>(bad),
                    static_cast<unsigned long long>(e.health.garbage_bytes));
      status += buf;
    }
  }
  if (loop.laser_silent()) status += " | LASER FAULT: pose on odometry alone";
  if (const int64_t tried = h.scan_matches + h.scan_match_fallbacks; tried > 0) {
    std::snprintf(buf, sizeof(buf), " | scan-matched %.0f%%",
                  100.0 * static_cast<double>(h.scan_matches) / static_cast<double>(tried));
    status += buf;
  }
  // The pose published last (dead-reckoned while the laser is away), not the atlas's own.
  const DominantOutput& p = loop.published_pose();
  std::snprintf(buf, sizeof(buf), " | pose f%d (%.2f, %.2f, %.2f) q %.2f | rss %.1f MB",
                p.valid ? p.frame : -1, p.pose.mean.x, p.pose.mean.y, p.pose.mean.theta, p.q,
                static_cast<double>(h.resident_memory_bytes) / 1e6);
  status += buf;
  h.status = status;
  h.version = AtlasVersion();
  return h;
}

}  // namespace atlas
