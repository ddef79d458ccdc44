#include "tools/cli/tool_options.h"

#include <gtest/gtest.h>

namespace atlas::cli {
namespace {

TEST(ToolOptions, NumbersInRangeAndAbsentOptions) {
  const ToolOptions o{{{"--runs", "50"}, {"--seed", "x"}}};
  double runs = 1, seed = 0, absent = 7;
  std::string error;
  EXPECT_TRUE(GetNumberOption(o, "--runs", 1, 100, runs, error));
  EXPECT_EQ(runs, 50);
  EXPECT_TRUE(GetNumberOption(o, "--minutes", 0, 10, absent, error));
  EXPECT_EQ(absent, 7);
  EXPECT_FALSE(GetNumberOption(o, "--seed", 0, 10, seed, error));
  EXPECT_NE(error.find("--seed"), std::string::npos);
  EXPECT_FALSE(GetNumberOption(o, "--runs", 1, 10, runs, error));  // out of range
  EXPECT_EQ(error, "--runs must be a number in [1, 10], got '50'");
}

TEST(ToolOptions, GetIntegerAndSeedOptions) {
  const ToolOptions o{{{"--runs", "1.5"}, {"--seed", "3"}, {"--per-run", "1"}}};
  int runs = 50, per_run = 0, ring = 24;
  uint64_t seed = 1;
  std::string error;
  EXPECT_FALSE(GetIntegerOption(o, "--runs", 1, 10000, runs, error));
  EXPECT_EQ(error, "--runs must be an integer in [1, 10000], got '1.5'");
  EXPECT_EQ(runs, 50);
  EXPECT_TRUE(GetIntegerOption(o, "--per-run", 0, 1, per_run, error));
  EXPECT_EQ(per_run, 1);
  EXPECT_TRUE(GetIntegerOption(o, "--ring", 16, 24, ring, error));  // absent
  EXPECT_EQ(ring, 24);
  EXPECT_TRUE(GetSeedOption(o, "--seed", seed, error));
  EXPECT_EQ(seed, 3u);
}

}  // namespace
}  // namespace atlas::cli
