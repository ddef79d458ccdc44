// Round trip, a slice of mit-csail in the unit suite: the fake devices play the log's first
// scans as device bytes over ptys and the fake CAN bus; the drivers decode them; every scan,
// odometry step and sonar reading must come out, equal to what was played.
#include <gtest/gtest.h>

#include <cstdio>

#include "tests/hil_drivers/driver_rig.h"
#include "tests/hil_drivers/round_trip_check.h"

namespace atlas::hil {
namespace {

TEST(RoundTripTest, MitCsailSliceAt20x) {
  std::string error;
  auto rec = LoadMitCsail(120, &error);
  if (!rec) GTEST_SKIP() << "mit-csail not available: " << error;
  RigOptions o;
  o.speed = 20.0;
  DriverRig rig(rec, o);
  ASSERT_TRUE(rig.Start(&error)) << error;
  rig.RunToEnd(std::chrono::seconds(20));
  CheckRoundTrip(rig, /*expect_all=*/true);
}

}  // namespace
}  // namespace atlas::hil
