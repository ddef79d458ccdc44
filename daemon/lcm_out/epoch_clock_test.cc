#include "daemon/lcm_out/epoch_clock.h"

#include <gtest/gtest.h>

#include <chrono>

namespace atlas {
namespace {

int64_t RealtimeMicroseconds() {
  return std::chrono::duration_cast<std::chrono::microseconds>(
             std::chrono::system_clock::now().time_since_epoch())
      .count();
}

TEST(EpochClockTest, CapturedUtimeIsTheWallClockNow) {
  const EpochClock epoch = EpochClock::Capture();
  const int64_t before = RealtimeMicroseconds();
  const int64_t utime = epoch.Utime(Now());
  const int64_t after = RealtimeMicroseconds();
  // Within the two wall-clock readings (and the microsecond the captures round away).
  EXPECT_GE(utime, before - 2);
  EXPECT_LE(utime, after + 2);
  // After 2020: microseconds since the epoch, not the monotonic clock's seconds since boot.
  EXPECT_GT(utime, int64_t{1577836800} * 1000000);
}

TEST(EpochClockTest, BothDirectionsAreExactInverses) {
  const EpochClock epoch(1796166934000000 - 834900104);
  const Time stamp = Time(std::chrono::microseconds(834900104));
  EXPECT_EQ(epoch.Utime(stamp), 1796166934000000);
  EXPECT_EQ(epoch.Stamp(epoch.Utime(stamp)), stamp);
  EXPECT_EQ(epoch.ToMonotonic(epoch.ToEpoch(-5)), -5);
  // A stamp is published in whole microseconds, as the raw channels carry it.
  const Time fine = stamp + std::chrono::nanoseconds(999);
  EXPECT_EQ(epoch.Stamp(epoch.Utime(fine)), stamp);
}

TEST(EpochClockTest, TwoCapturesAgree) {
  const EpochClock a = EpochClock::Capture();
  const EpochClock b = EpochClock::Capture();
  EXPECT_NEAR(static_cast<double>(a.offset_us()), static_cast<double>(b.offset_us()), 50.0);
}

TEST(EpochClockTest, DefaultIsTheMonotonicClock) {
  const Time t = FromSeconds(12.345678);
  EXPECT_EQ(EpochClock().Utime(t), 12345678);
}

}  // namespace
}  // namespace atlas
