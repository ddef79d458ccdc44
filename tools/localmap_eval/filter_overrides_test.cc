#include "tools/localmap_eval/filter_overrides.h"

#include <gtest/gtest.h>

namespace atlas::localmap_eval {
namespace {

TEST(FilterOverrides, SetsNamedFields) {
  LocalMapOptions o;
  EXPECT_EQ(ApplyOverrides("range_sigma=0.02,min_points=12,joint_gate=0.999", o), "");
  EXPECT_DOUBLE_EQ(o.extraction.range_sigma, 0.02);
  EXPECT_EQ(o.extraction.min_points, 12);
  EXPECT_DOUBLE_EQ(o.association.joint_gate, 0.999);
}

TEST(FilterOverrides, EmptySpecChangesNothing) {
  LocalMapOptions o;
  const double before = o.extraction.range_sigma;
  EXPECT_EQ(ApplyOverrides("", o), "");
  EXPECT_DOUBLE_EQ(o.extraction.range_sigma, before);
}

TEST(FilterOverrides, RefusesUnknownNamesNonNumbersAndFractionalIntegers) {
  for (const char* bad : {"no_such=1", "range_sigma", "range_sigma=abc", "min_points=2.5"}) {
    LocalMapOptions o;
    const std::string e = ApplyOverrides(bad, o);
    EXPECT_NE(e.find("--set: bad item"), std::string::npos) << bad;
    EXPECT_NE(e.find("min_points (integer)"), std::string::npos) << bad;
  }
}

TEST(FilterOverrides, RefusesInvalidResult) {
  LocalMapOptions o;
  EXPECT_FALSE(ApplyOverrides("range_sigma=-1", o).empty());
}

}  // namespace
}  // namespace atlas::localmap_eval
