#include "core/common/parse_number.h"

#include <gtest/gtest.h>

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

}  // namespace
}  // namespace atlas
