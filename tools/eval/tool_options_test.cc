#include "tools/eval/tool_options.h"

#include <gtest/gtest.h>

namespace atlas::eval {
namespace {

TEST(ToolOptions, KnownKeysWithValuesAndNumbersInRange) {
  const char* argv_c[] = {"tool", "mc", "--runs", "50", "--seed", "x"};
  char** argv = const_cast<char**>(argv_c);
  const ToolOptions o = ParseToolOptions(6, argv, 2, {"--runs", "--seed"});
  ASSERT_TRUE(o.error.empty()) << o.error;
  double runs = 1, seed = 0, absent = 7;
  std::string error;
  EXPECT_TRUE(GetNumberOption(o, "--runs", 1, 100, runs, error));
  EXPECT_EQ(runs, 50);
  EXPECT_TRUE(GetNumberOption(o, "--minutes", 0, 10, absent, error));
  EXPECT_EQ(absent, 7);
  EXPECT_FALSE(GetNumberOption(o, "--seed", 0, 10, seed, error));
  EXPECT_NE(error.find("--seed"), std::string::npos);
  EXPECT_FALSE(GetNumberOption(o, "--runs", 1, 10, runs, error));  // out of range
  EXPECT_NE(ParseToolOptions(6, argv, 2, {"--runs"}).error.find("unknown option '--seed'"),
            std::string::npos);
  EXPECT_NE(ParseToolOptions(5, argv, 2, {"--runs", "--seed"}).error.find("needs a value"),
            std::string::npos);
}

TEST(ToolOptions, GetIntegerAndSeedOptions) {
  const char* argv_c[] = {"tool", "mc", "--runs", "1.5", "--seed", "3", "--per-run", "1"};
  char** argv = const_cast<char**>(argv_c);
  const ToolOptions o = ParseToolOptions(8, argv, 2, {"--runs", "--seed", "--per-run", "--ring"});
  ASSERT_TRUE(o.error.empty()) << o.error;
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
}  // namespace atlas::eval
