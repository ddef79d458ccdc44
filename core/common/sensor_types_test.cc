#include "core/common/sensor_types.h"

#include <gtest/gtest.h>

namespace atlas {
namespace {

LaserScan ScanWithRanges(float max_range, std::vector<float> ranges) {
  LaserScan s;
  s.max_range = max_range;
  s.ranges = std::move(ranges);
  return s;
}

TEST(LimitLaserRange, ReturnsAtOrBeyondTheSettingAreNoReturn) {
  LaserScan s = ScanWithRanges(81.82f, {1.0f, 7.99f, 8.0f, 50.0f, kNoReturn});
  LimitLaserRange(&s, 8.0f);
  EXPECT_EQ(s.ranges[0], 1.0f);
  EXPECT_EQ(s.ranges[1], 7.99f);
  EXPECT_FALSE(IsReturn(s.ranges[2]));
  EXPECT_FALSE(IsReturn(s.ranges[3]));
  EXPECT_FALSE(IsReturn(s.ranges[4]));
  EXPECT_EQ(s.max_range, 8.0f);
}

// A setting above the scanner's own maximum does not raise the maximum the scan states.
TEST(LimitLaserRange, KeepsTheSmallerMaximum) {
  LaserScan s = ScanWithRanges(8.182f, {8.1f});
  LimitLaserRange(&s, 30.0f);
  EXPECT_EQ(s.ranges[0], 8.1f);
  EXPECT_EQ(s.max_range, 8.182f);
  LaserScan unknown = ScanWithRanges(0.0f, {12.0f, 31.0f});
  LimitLaserRange(&unknown, 30.0f);
  EXPECT_EQ(unknown.ranges[0], 12.0f);
  EXPECT_FALSE(IsReturn(unknown.ranges[1]));
  EXPECT_EQ(unknown.max_range, 30.0f);
}

}  // namespace
}  // namespace atlas
