#include "core/common/parse_number.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <string>
#include <string_view>

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

TEST(ParseNumber, AcceptsPlainDecimalAndExponentForms) {
  const struct {
    const char* text;
    double value;
  } good[] = {{"-1.5", -1.5}, {"2e-3", 2e-3}, {"1e3", 1000}, {"1E+3", 1000}, {"0", 0},
              {".5", 0.5},    {"5.", 5},      {"-.5", -0.5}, {"007", 7},     {"4e-320", 4e-320}};
  for (const auto& [text, value] : good) {
    SCOPED_TRACE(text);
    double v = -7;
    EXPECT_TRUE(ParseNumber(text, &v));
    EXPECT_EQ(v, value);
  }
  double v = 7;
  EXPECT_TRUE(ParseNumber("-0", &v));
  EXPECT_EQ(v, 0);
  EXPECT_TRUE(std::signbit(v));
}

// strtod took leading spaces, '+', hex and the locale's decimal point; from_chars takes none.
TEST(ParseNumber, RefusesWhatStrtodWouldHaveTaken) {
  for (const char* bad : {" 5",     "5 ",     "\t5", "5\n", "+5",     "0x10", "0X1p3", "1e999",
                          "-1e999", "1e-400", "nan", "NAN", "nan(1)", "inf",  "INF",   "infinity",
                          "",       ".",      "-",   "1e",  "1e+",    "--1",  "1_0"}) {
    SCOPED_TRACE(bad);
    double v = -7;
    EXPECT_FALSE(ParseNumber(bad, &v));
    EXPECT_EQ(v, -7);
  }
}

TEST(ParseNumber, ReadsOnlyTheGivenView) {
  const std::string_view line = "12.5 7 -3x";
  double v = 0;
  EXPECT_TRUE(ParseNumber(line.substr(0, 4), &v));
  EXPECT_EQ(v, 12.5);
  EXPECT_TRUE(ParseNumber(line.substr(5, 1), &v));
  EXPECT_EQ(v, 7);
  EXPECT_FALSE(ParseNumber(line.substr(7), &v));  // "-3x"
  EXPECT_TRUE(ParseNumber(line.substr(7, 2), &v));
  EXPECT_EQ(v, -3);
  EXPECT_FALSE(ParseNumber(std::string_view(), &v));
  EXPECT_EQ(v, -3);
  int64_t i = 0;
  EXPECT_TRUE(ParseInteger(line.substr(5, 1), &i));
  EXPECT_EQ(i, 7);
  EXPECT_FALSE(ParseInteger(line.substr(0, 4), &i));
  EXPECT_EQ(i, 7);
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
  int n = 0;
  EXPECT_TRUE(ParseInteger("-2147483648", &n));
  EXPECT_EQ(n, INT32_MIN);
  EXPECT_TRUE(ParseInteger("2147483647", &n));
  EXPECT_EQ(n, INT32_MAX);
  EXPECT_FALSE(ParseInteger("2147483648", &n));
  EXPECT_FALSE(ParseInteger("-2147483649", &n));
  EXPECT_FALSE(ParseInteger("+1", &n));
  EXPECT_EQ(n, INT32_MAX);
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
  for (const char* bad :
       {"5x", "", "nan", "inf", "1e999", "-1e999", "11", "-0.5", "abc", " 5", "+5", "0x1"}) {
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
