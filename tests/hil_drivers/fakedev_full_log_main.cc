// HIL round trip (ctest label "hil"): atlas-fakedev plays the whole of mit-csail (1988 scans,
// 424 s) at 10x real time into the drivers; ~45 s.
#include <gtest/gtest.h>

#include "tests/hil_drivers/fakedev_round_trip.h"

TEST(FakedevFullLogTest, MitCsailAt10x) { atlas::hil::RunFakedevRoundTrip(0, 10.0); }
