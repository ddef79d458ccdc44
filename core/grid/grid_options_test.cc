#include "core/grid/grid_options.h"

#include <gtest/gtest.h>

namespace atlas {
namespace {

TEST(GridOptions, DefaultsAreValid) { EXPECT_EQ(GridOptions().Validate(), ""); }

TEST(GridOptions, EachPartIsChecked) {
  GridOptions o;
  o.grid.hit_probability = 0.4;
  EXPECT_NE(o.Validate(), "");
  o = GridOptions();
  o.grid.initial_cells = o.grid.max_cells + 1;
  EXPECT_NE(o.Validate(), "");
  o = GridOptions();
  o.range.no_return_free_range = o.range.max_range + 1.0;
  EXPECT_NE(o.Validate(), "");
  o = GridOptions();
  o.alignment.degenerate_ratio = 0.0;
  EXPECT_NE(o.Validate(), "");
  o = GridOptions();
  o.search.depth = 0;
  EXPECT_NE(o.Validate(), "");
  o = GridOptions();
  o.search.peak_angle = -0.1;
  EXPECT_NE(o.Validate(), "");
}

}  // namespace
}  // namespace atlas
