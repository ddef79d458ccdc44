#include "formats/occupancy_grid.h"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

namespace atlas::formats {
namespace {

using ::testing::HasSubstr;

TEST(OccupancyGrid, OccupiedCellsCoverThePointsWithAMargin) {
  const std::vector<Vec2> points = {Vec2(0.05, 0.05), Vec2(1.95, 0.95)};
  const OccupancyGrid g = OccupiedCellsGrid(points, 0.1, 0.5);
  EXPECT_DOUBLE_EQ(g.origin.x(), -0.5);
  EXPECT_DOUBLE_EQ(g.origin.y(), -0.5);
  EXPECT_EQ(g.width, 31);   // -0.5 .. 2.45 and one more cell
  EXPECT_EQ(g.height, 21);  // -0.5 .. 1.45 and one more cell
  int ix = 0, iy = 0;
  ASSERT_TRUE(g.CellOf(points[1], &ix, &iy));
  EXPECT_EQ(g.At(ix, iy), Occupancy::kOccupied);
  int occupied = 0;
  for (Occupancy c : g.cells) occupied += c == Occupancy::kOccupied;
  EXPECT_EQ(occupied, 2);
  EXPECT_EQ(g.At(0, 0), Occupancy::kUnknown);
  EXPECT_EQ(OccupiedCellsGrid({}, 0.1, 0.5).width, 0);
}

// The PGM's header and size, and its rows top first: the bottom-left occupied cell is in the
// image's last row.
TEST(OccupancyGrid, PgmHeaderSizeAndRowOrder) {
  const std::vector<Vec2> points = {Vec2(0.05, 0.05)};
  const OccupancyGrid g = OccupiedCellsGrid(points, 0.1, 0.2);
  const std::string pgm = FormatPgm(g, "test");
  EXPECT_EQ(pgm.rfind("P5\n# test\n", 0), 0u);
  PgmImage image;
  ASSERT_EQ(ParsePgm(pgm, "m.pgm", &image), "");
  EXPECT_EQ(image.width, g.width);
  EXPECT_EQ(image.height, g.height);
  EXPECT_EQ(image.maxval, 255);
  ASSERT_EQ(image.pixels.size(), static_cast<size_t>(g.width * g.height));
  int ix = 0, iy = 0;
  ASSERT_TRUE(g.CellOf(points[0], &ix, &iy));
  const int row = g.height - 1 - iy;
  EXPECT_EQ(image.pixels[static_cast<size_t>(row * g.width + ix)], 0);  // occupied: black
  EXPECT_EQ(image.pixels[0], 205);                                      // unknown: grey
  EXPECT_THAT(ParsePgm(pgm.substr(0, pgm.size() - 1), "m.pgm", &image),
              HasSubstr("m.pgm: the header says"));
  EXPECT_EQ(ParsePgm("P2\n1 1\n255\n0\n", "m.pgm", &image),
            "m.pgm: not a binary PGM (the file does not begin with P5)");
}

TEST(OccupancyGrid, YamlHasTheMapServerKeys) {
  const OccupancyGrid g = OccupiedCellsGrid(std::vector<Vec2>{Vec2(3.0, -2.0)}, 0.05, 1.0);
  const std::string yaml = FormatMapYaml(g, "map.pgm");
  MapYaml m;
  ASSERT_EQ(ParseMapYaml(yaml, "map.yaml", &m), "");
  EXPECT_EQ(m.image, "map.pgm");
  EXPECT_EQ(m.mode, "trinary");
  EXPECT_DOUBLE_EQ(m.resolution, 0.05);
  EXPECT_NEAR(m.origin.x, g.origin.x(), 1e-6);
  EXPECT_NEAR(m.origin.y, g.origin.y(), 1e-6);
  EXPECT_EQ(m.origin.theta, 0.0);
  EXPECT_EQ(m.negate, 0);
  EXPECT_DOUBLE_EQ(m.occupied_thresh, 0.65);
  EXPECT_DOUBLE_EQ(m.free_thresh, 0.196);
  // map_server reads the written pixels as intended: (255 - p) / 255 against the thresholds.
  EXPECT_GT((255.0 - 0) / 255, m.occupied_thresh);
  EXPECT_LT((255.0 - 254) / 255, m.free_thresh);
  const double unknown = (255.0 - 205) / 255;
  EXPECT_TRUE(unknown > m.free_thresh && unknown < m.occupied_thresh);

  EXPECT_EQ(ParseMapYaml("image: a.pgm\nresolution: 0.1\n", "m.yaml", &m), "m.yaml: no key origin");
  EXPECT_EQ(ParseMapYaml("image: a.pgm\nimage: b.pgm\n", "m.yaml", &m),
            "m.yaml:2: key image repeats line 1");
  EXPECT_EQ(ParseMapYaml("colour: red\n", "m.yaml", &m), "m.yaml:1: unknown key 'colour'");
  EXPECT_EQ(ParseMapYaml("origin: [1, 2]\n", "m.yaml", &m),
            "m.yaml:1: origin must be [x, y, yaw], three numbers");
}

}  // namespace
}  // namespace atlas::formats
