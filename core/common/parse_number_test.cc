#include "core/common/parse_number.h"

#include <gtest/gtest.h>

#include <string>

namespace atlas {
namespace {

TEST(ParseNumber, TakesOnlyAWholeFiniteNumber) {
  double v = -7;
  EXPECT_TRUE(ParseNumber("2.5", &v));
  EXPECT_EQ(v, 2.5);
  EXPECT_TRUE(ParseNumber("-1e-3", &v));
  EXPECT_EQ(v, -1e-3);
  for (const char* bad : {"", "abc", "2.5s", "1e400", "nan", "inf", "-inf", "1,5", " "}) {
    SCOPED_TRACE(bad);
    v = -7;
    EXPECT_FALSE(ParseNumber(bad, &v));
    EXPECT_EQ(v, -7);  // left as it was
  }
}

TEST(ParseNumberIn, ChecksTheRange) {
  double v = -7;
  EXPECT_TRUE(ParseNumberIn("0.001", 0.001, 86400, &v));
  EXPECT_EQ(v, 0.001);
  EXPECT_TRUE(ParseNumberIn("86400", 0.001, 86400, &v));
  EXPECT_EQ(v, 86400);
  for (const char* bad : {"0", "-1", "86400.5", "1e300", "nan", "abc"}) {
    SCOPED_TRACE(bad);
    EXPECT_FALSE(ParseNumberIn(bad, 0.001, 86400, &v));
    EXPECT_EQ(v, 86400);
  }
}

TEST(ParseIntegerIn, TakesOnlyAWholeIntegerInTheRange) {
  long v = -7;
  EXPECT_TRUE(ParseIntegerIn("0", 0, 1000000, &v));
  EXPECT_EQ(v, 0);
  EXPECT_TRUE(ParseIntegerIn("20", 0, 1000000, &v));
  EXPECT_EQ(v, 20);
  for (const char* bad :
       {"", "-1", "1.5", "1e3", "abc", "20x", "1000001", "99999999999999999999999", "+5", " 5"}) {
    SCOPED_TRACE(bad);
    EXPECT_FALSE(ParseIntegerIn(bad, 0, 1000000, &v));
    EXPECT_EQ(v, 20);
  }
}

TEST(ParseInteger, TakesTheWholeRangeOfItsTypeAndNothingElse) {
  int64_t i = 0;
  EXPECT_TRUE(ParseInteger("-9223372036854775808", &i));
  EXPECT_EQ(i, INT64_MIN);
  EXPECT_FALSE(ParseInteger("9223372036854775808", &i));
  uint64_t u = 0;
  EXPECT_TRUE(ParseInteger("18446744073709551615", &u));
  EXPECT_EQ(u, UINT64_MAX);
  for (const char* bad : {"18446744073709551616", "-1", "+1", " 1", "1 ", "0x10", "1e3", ""}) {
    SCOPED_TRACE(bad);
    u = 7;
    EXPECT_FALSE(ParseInteger(bad, &u));
    EXPECT_EQ(u, 7u);
  }
}

TEST(OptionArguments, RangeMessagesPrintTheBoundsAsWritten) {
  std::string error;
  double d = 0;
  EXPECT_FALSE(NumberArgument("--minutes", "700", 0.05, 600, d, error));
  EXPECT_EQ(error, "--minutes must be a number in [0.05, 600], got '700'");
  int64_t n = 0;
  EXPECT_FALSE(IntegerArgument("--runs", "0", 1, 10000, n, error));
  EXPECT_EQ(error, "--runs must be an integer in [1, 10000], got '0'");
}

TEST(OptionArguments, NumbersAreWholeFiniteNumbersInRange) {
  double d = 2;
  std::string error;
  for (const char* bad : {"5x", "", "nan", "inf", "1e999", "-1e999", "11", "-0.5", "abc"}) {
    SCOPED_TRACE(bad);
    EXPECT_FALSE(NumberArgument("--budget", bad, 0, 10, d, error));
    EXPECT_EQ(error, std::string("--budget must be a number in [0, 10], got '") + bad + "'");
  }
  EXPECT_EQ(d, 2);  // unchanged on error
  EXPECT_TRUE(NumberArgument("--budget", "1e1", 0, 10, d, error));
  EXPECT_EQ(d, 10);
}

TEST(OptionArguments, IntegersAreWholeDecimalIntegersInRange) {
  int64_t n = 7;
  std::string error;
  for (const char* bad : {"1.5", "1e3", "", " 1", "1 ", "+1", "0x10", "1.0", "abc", "--1",
                          "9223372036854775808", "99999999999999999999999"}) {
    EXPECT_FALSE(ParseInteger(bad, &n)) << bad;
    EXPECT_FALSE(IntegerArgument("--runs", bad, 1, 10000, n, error)) << bad;
    EXPECT_NE(error.find("--runs must be an integer in [1, 10000], got '"), std::string::npos);
  }
  EXPECT_EQ(n, 7);  // unchanged on error
  EXPECT_TRUE(IntegerArgument("--jump-mm", "-5", -100, 100, n, error));
  EXPECT_EQ(n, -5);
  EXPECT_TRUE(ParseInteger("-9223372036854775808", &n));
  EXPECT_EQ(n, INT64_MIN);
  int small = 0;
  EXPECT_TRUE(IntegerArgument("--rooms", "16", 1, 100000, small, error));
  EXPECT_EQ(small, 16);
  EXPECT_FALSE(IntegerArgument("--rooms", "100001", 1, 100000, small, error));
  EXPECT_EQ(small, 16);
}

TEST(OptionArguments, SeedsCoverTheWholeUnsigned64BitRange) {
  uint64_t seed = 1;
  std::string error;
  EXPECT_TRUE(SeedArgument("--seed", "18446744073709551615", seed, error));
  EXPECT_EQ(seed, UINT64_MAX);
  EXPECT_TRUE(SeedArgument("--seed", "0", seed, error));
  EXPECT_EQ(seed, 0u);
  for (const char* bad : {"18446744073709551616", "99999999999999999999999", "-1", "1e3", "1.7"}) {
    EXPECT_FALSE(SeedArgument("--seed", bad, seed, error)) << bad;
    EXPECT_EQ(error, std::string("--seed must be an integer in [0, 18446744073709551615], got '") +
                         bad + "'");
  }
  EXPECT_EQ(seed, 0u);
}

}  // namespace
}  // namespace atlas
