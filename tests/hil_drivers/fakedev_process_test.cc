// atlas-fakedev as a separate process: --help, bad arguments, and a round trip of a slice of
// mit-csail into the drivers over its ptys and fake CAN bus.
#include <gtest/gtest.h>

#include <cstdio>
#include <string>
#include <utility>

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

// atlas-fakedev's exit status and what it printed (stdout and stderr).
std::string RunOutput(const std::string& args, int* status) {
  std::FILE* p = popen((std::string(ATLAS_FAKEDEV) + " " + args + " 2>&1").c_str(), "r");
  std::string out;
  if (p == nullptr) return out;
  char buf[512];
  while (std::fgets(buf, sizeof buf, p) != nullptr) out += buf;
  *status = WEXITSTATUS(pclose(p));
  return out;
}

TEST(FakedevProcessTest, OptionsAreRangeCheckedBeforeTheLogIsRead) {
  const std::pair<const char*, const char*> cases[] = {
      {"--jump-mm 5000000000", "--jump-mm must be an integer in [-2147483648, 2147483647]"},
      {"--garbage-every 2147483648", "--garbage-every must be an integer in [0, 2147483647]"},
      {"--max-scans 1.5", "--max-scans must be an integer in [0, "},
      {"--drop-after -5 --drop-for 1", "--drop-after must be a number in [0, 1000000]"},
      {"--progress-every -1", "--progress-every must be a number in [0, 1000000]"},
      {"--stall-for 2", "--stall-after S and --stall-for T go together"},
      {"--drop-after 1", "--drop-after S and --drop-for T go together"},
  };
  for (const auto& [args, message] : cases) {
    int status = -1;
    const std::string out = RunOutput(std::string("--log /nonexistent.clf ") + args, &status);
    EXPECT_EQ(status, 2) << args;
    EXPECT_NE(out.find(message), std::string::npos) << args << ": " << out;
  }
}

TEST(FakedevProcessTest, RoundTripSliceAt20x) { RunFakedevRoundTrip(100, 20.0); }

}  // namespace
}  // namespace atlas::hil
