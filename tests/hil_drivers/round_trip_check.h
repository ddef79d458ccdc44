#pragma once
// Assertions shared by the round-trip tests (unit slice and the full "hil" run).

#include <gtest/gtest.h>

#include <cstdio>

#include "tests/hil_drivers/driver_rig.h"

namespace atlas::hil {

// Pose step of the driver between samples a and b vs the recording's between the same ticks.
inline void CheckOdometry(const std::vector<fake::SentOdometry>& sent,
                          const std::vector<OdometrySample>& got, bool expect_all) {
  if (expect_all) {
    EXPECT_EQ(got.size(), sent.size()) << "odometry samples out vs 0x311 frames in";
  }
  const size_t n = std::min(sent.size(), got.size());
  // The fake drives each 20 ms step of the log as one arc (a differential drive cannot move
  // sideways): the driver must reproduce that arc to the counters' precision. How far the
  // log's own step is from an arc is reported as well.
  double worst_xy = 0, worst_th = 0, worst_sideways = 0;
  for (size_t k = 1; k < n; ++k) {
    // Only consecutive ticks: across a fault (jump, drop, stall) the driver's step spans
    // ticks that were never sent or were skipped.
    if (sent[k].tick != sent[k - 1].tick + 1) continue;
    const Pose2 log_step = Between(sent[k - 1].pose, sent[k].pose);
    const double chord = std::copysign(std::hypot(log_step.x, log_step.y), log_step.x);
    const Pose2 arc{chord * std::cos(0.5 * log_step.theta), chord * std::sin(0.5 * log_step.theta),
                    log_step.theta};
    const Pose2 have = Between(got[k - 1].pose, got[k].pose);
    worst_xy = std::max(worst_xy, std::hypot(arc.x - have.x, arc.y - have.y));
    worst_th = std::max(worst_th, std::abs(WrapAngle(arc.theta - have.theta)));
    worst_sideways = std::max(worst_sideways, std::hypot(arc.x - log_step.x, arc.y - log_step.y));
  }
  // Over the whole run: the integrated pose against the log's, relative to the first sample.
  double end_xy = 0, end_th = 0;
  if (n > 1) {
    const Pose2 want = Between(sent[0].pose, sent[n - 1].pose);
    const Pose2 have = Between(got[0].pose, got[n - 1].pose);
    end_xy = std::hypot(want.x - have.x, want.y - have.y);
    end_th = std::abs(WrapAngle(want.theta - have.theta));
  }
  std::printf(
      "odometry: %zu frames 0x311 sent intact, %zu samples out; worst step error %.4f m "
      "%.5f rad (log's own sideways motion up to %.4f m per step); end-to-end error "
      "%.4f m %.5f rad over %.1f m of log\n",
      sent.size(), got.size(), worst_xy, worst_th, worst_sideways, end_xy, end_th,
      n > 1 ? std::hypot(sent[n - 1].pose.x - sent[0].pose.x, sent[n - 1].pose.y - sent[0].pose.y)
            : 0.0);
  // Counters are whole millimetres: each wheel's change over a step is within 1 mm of the
  // exact one, so the arc length within 1 mm and the heading within 2 mm / 0.58 m.
  EXPECT_LT(worst_xy, 0.0015);
  EXPECT_LT(worst_th, 0.0035);
}

inline bool SameReading(const SonarReading& a, const SonarReading& b) {
  if (a.returns.size() != b.returns.size()) return false;
  for (size_t i = 0; i < a.returns.size(); ++i) {
    const SonarReturn& x = a.returns[i];
    const SonarReturn& y = b.returns[i];
    if (x.transducer != y.transducer || IsReturn(x.range) != IsReturn(y.range) ||
        (IsReturn(x.range) && std::abs(x.range - y.range) > 0.0006f))
      return false;
  }
  return true;
}

// Every reading out must be one of the SIPs sent intact, in order. (SIPs sent while the
// driver was away, e.g. during its reconnection, are legitimately missing.) Returns how many
// unbroken runs of consecutive sent SIPs are missing.
inline size_t CheckSonar(const std::vector<SonarReading>& sent,
                         const std::vector<SonarReading>& got, bool expect_all) {
  if (expect_all) {
    EXPECT_EQ(got.size(), sent.size()) << "sonar readings out vs SIPs in";
  }
  const InOrderMatch m = MatchInOrder(
      sent.size(), got, [&](size_t k, const SonarReading& r) { return SameReading(sent[k], r); });
  std::printf(
      "sonar: %zu SIPs with returns sent intact, %zu readings out, %zu not matching, %zu runs "
      "missing\n",
      sent.size(), got.size(), m.unmatched, m.missing_runs);
  EXPECT_EQ(m.unmatched, 0u);
  return m.missing_runs;
}

inline void PrintHealthAndCheck(const DriverRig& rig, bool expect_all);

// Unbroken runs of consecutive messages sent intact that did not come out (the laser's are
// counted only without expect_all, which compares every scan instead).
struct MissingRuns {
  size_t laser = 0;
  size_t sonar = 0;
};

inline MissingRuns CheckRoundTrip(const DriverRig& rig, bool expect_all) {
  // The comparisons need every message sent: none may have left the fakes' bounded records.
  EXPECT_EQ(rig.lms_->sent_intact().dropped(), 0u);
  EXPECT_EQ(rig.base_->sent_intact().dropped(), 0u);
  EXPECT_EQ(rig.p2os_->sent_intact().dropped(), 0u);
  const auto sent = rig.lms_->sent_intact().Items();
  std::string first;
  size_t missing = 0;
  MissingRuns runs;
  const size_t bad = expect_all
                         ? CompareScans(*rig.rec_, sent, rig.scans, &first)
                         : CompareScansInOrder(*rig.rec_, sent, rig.scans, &missing, &runs.laser);
  size_t no_return = 0;
  for (const auto& s : rig.scans)
    for (float r : s.ranges) no_return += !IsReturn(r);
  std::printf(
      "laser: %zu scans in the slice, %zu sent intact, %zu out, %zu differ, "
      "%zu no-return beams out, %zu runs missing\n",
      rig.rec_->scans.size(), sent.size(), rig.scans.size(), bad, no_return, runs.laser);
  EXPECT_EQ(bad, 0u) << first;
  if (expect_all) {
    EXPECT_EQ(sent.size(), rig.rec_->scans.size());
    EXPECT_EQ(rig.scans.size(), rig.rec_->scans.size());
  }
  CheckOdometry(rig.base_->sent_intact().Items(), rig.odometry, expect_all);
  runs.sonar = CheckSonar(rig.p2os_->sent_intact().Items(), rig.sonar, expect_all);
  PrintHealthAndCheck(rig, expect_all);
  return runs;
}

inline void PrintHealthAndCheck(const DriverRig& rig, bool expect_all) {
  for (const DriverHealth& h : {rig.laser_->Health(), rig.odo_->Health(), rig.sonar_->Health()}) {
    std::printf(
        "  %-40s %-8s msgs %6llu samples %6llu crc %llu garbage %llu trunc %llu "
        "disc %llu drops %llu reconnects %llu rate %.1f Hz\n",
        h.device.c_str(), ToString(h.state), (unsigned long long)h.messages,
        (unsigned long long)h.samples, (unsigned long long)h.bad_crc,
        (unsigned long long)h.garbage_bytes, (unsigned long long)h.truncated,
        (unsigned long long)h.discontinuities, (unsigned long long)h.drops,
        (unsigned long long)h.reconnects, h.message_rate_hz);
    if (expect_all) {
      EXPECT_EQ(h.bad_crc, 0u) << h.device;
      EXPECT_EQ(h.drops, 0u) << h.device;
      EXPECT_EQ(h.discontinuities, 0u) << h.device;
      EXPECT_EQ(h.disconnects, 0u) << h.device;
    }
  }
}

}  // namespace atlas::hil
