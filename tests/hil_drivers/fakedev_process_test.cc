// atlas-fakedev as a separate process: --help, bad arguments, and a round trip of a slice of
// mit-csail into the drivers over its ptys and fake CAN bus.
#include <gtest/gtest.h>

#include "tests/hil_drivers/fakedev_round_trip.h"

namespace atlas::hil {
namespace {

int RunQuiet(const std::string& args) {
  return std::system((std::string(ATLAS_FAKEDEV) + " " + args + " >/dev/null 2>&1").c_str());
}

TEST(FakedevProcessTest, HelpAndBadArguments) {
  EXPECT_EQ(WEXITSTATUS(RunQuiet("--help")), 0);
  EXPECT_EQ(WEXITSTATUS(RunQuiet("")), 2);                        // no --log
  EXPECT_EQ(WEXITSTATUS(RunQuiet("--log x --speed -1")), 2);      // bad speed
  EXPECT_EQ(WEXITSTATUS(RunQuiet("--log /nonexistent.clf")), 2);  // unreadable log
  EXPECT_EQ(WEXITSTATUS(RunQuiet("--log x --only wheel")), 2);
  EXPECT_EQ(WEXITSTATUS(RunQuiet("--bogus")), 2);
}

TEST(FakedevProcessTest, RoundTripSliceAt20x) { RunFakedevRoundTrip(100, 20.0); }

}  // namespace
}  // namespace atlas::hil
