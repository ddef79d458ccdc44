#include "daemon/atlasd/input_drain.h"

#include <gtest/gtest.h>

#include <string>
#include <vector>

namespace atlas {
namespace {

// What a drain handed on, in order: "o", "s" or "l" with the stamp in nanoseconds.
class Recorder final : public DrainTarget {
 public:
  void OnOdometry(const OdometrySample& s) override { Add("o", s.stamp); }
  void OnSonar(SonarReading& r) override { Add("s", r.stamp); }
  void OnScan(LaserScan& l) override { Add("l", l.stamp); }
  std::vector<std::string> items;

 private:
  void Add(const char* kind, Time t) {
    items.push_back(kind + std::to_string(t.time_since_epoch().count()));
  }
};

Time Us(int64_t us) { return Time(std::chrono::microseconds(us)); }

OdometrySample Odometry(Time t) {
  OdometrySample s;
  s.stamp = t;
  return s;
}
SonarReading Sonar(Time t) {
  SonarReading r;
  r.stamp = t;
  return r;
}
LaserScan Scan(Time t) {
  LaserScan l;
  l.stamp = t;
  return l;
}

// The odometry first; then readings and scans merged by stamp, a scan before a reading of the
// same stamp.
TEST(InputDrain, OdometryFirstThenReadingsAndScansInStampOrder) {
  SpscQueue<OdometrySample> odometry(8);
  SpscQueue<SonarReading> sonar(8);
  SpscQueue<LaserScan> laser(8);
  for (int64_t t : {100, 300, 500}) sonar.Push(Sonar(Us(t)));
  for (int64_t t : {200, 300, 600}) laser.Push(Scan(Us(t)));
  for (int64_t t : {50, 150, 700}) odometry.Push(Odometry(Us(t)));
  InputDrain drain(&odometry, &sonar, &laser);
  Recorder r;
  drain.Drain(&r);
  EXPECT_EQ(r.items, (std::vector<std::string>{"o50000", "o150000", "o700000", "s100000", "l200000",
                                               "l300000", "s300000", "s500000", "l600000"}));
  Recorder again;
  drain.Drain(&again);
  EXPECT_TRUE(again.items.empty());
}

// Stamps are handed on as the drivers made them, to the nanosecond: the StepLoop, not the
// drain, truncates them to the raw channels' resolution.
TEST(InputDrain, StampsAreHandedOnAsMade) {
  SpscQueue<OdometrySample> odometry(4);
  SpscQueue<LaserScan> laser(4);
  odometry.Push(Odometry(Time(std::chrono::nanoseconds(1'000'499))));
  laser.Push(Scan(Time(std::chrono::nanoseconds(2'000'999))));
  InputDrain drain(&odometry, nullptr, &laser);
  Recorder r;
  drain.Drain(&r);
  EXPECT_EQ(r.items, (std::vector<std::string>{"o1000499", "l2000999"}));
}

// One drain takes at most one queue's capacity of readings and of scans: a loop that falls
// behind steps what it holds before it takes more.
TEST(InputDrain, TakesAtMostOneCapacityOfEachPerDrain) {
  SpscQueue<SonarReading> sonar(4);
  SpscQueue<LaserScan> laser(2);
  SpscQueue<OdometrySample> odometry(2);
  InputDrain drain(&odometry, &sonar, &laser);
  for (int64_t t = 1; t <= 4; ++t) sonar.Push(Sonar(Us(10 * t)));
  for (int64_t t = 1; t <= 2; ++t) laser.Push(Scan(Us(10 * t + 5)));
  Recorder first;
  drain.Drain(&first);
  EXPECT_EQ(first.items.size(), 6u);
  // Refilled while the loop steps: the next drain is bounded the same way.
  for (int64_t t = 5; t <= 8; ++t) sonar.Push(Sonar(Us(10 * t)));
  laser.Push(Scan(Us(55)));
  Recorder second;
  drain.Drain(&second);
  EXPECT_EQ(second.items,
            (std::vector<std::string>{"s50000", "l55000", "s60000", "s70000", "s80000"}));
}

TEST(InputDrain, DisabledDevicesAreSkipped) {
  SpscQueue<OdometrySample> odometry(4);
  odometry.Push(Odometry(Us(1)));
  InputDrain drain(&odometry, nullptr, nullptr);
  Recorder r;
  drain.Drain(&r);
  EXPECT_EQ(r.items, (std::vector<std::string>{"o1000"}));
}

}  // namespace
}  // namespace atlas
