#include "formats/ply_points.h"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

namespace atlas::formats {
namespace {

using ::testing::HasSubstr;

TEST(PlyPoints, WrittenThenReadBack) {
  const std::vector<PlyPoint> points = {{Vec2(1.25, -2.5), 0}, {Vec2(0.1, 0.2), 7}};
  const std::string text = FormatPlyPoints(points, "kept points");
  EXPECT_EQ(text,
            "ply\nformat ascii 1.0\ncomment kept points\nelement vertex 2\nproperty float x\n"
            "property float y\nproperty float z\nproperty int frame\nend_header\n"
            "1.250 -2.500 0 0\n0.100 0.200 0 7\n");
  std::vector<PlyPoint> read;
  ASSERT_EQ(ParsePlyPoints(text, "p.ply", &read), "");
  ASSERT_EQ(read.size(), 2u);
  EXPECT_EQ(read[1].frame, 7);
  EXPECT_DOUBLE_EQ(read[0].p.y(), -2.5);
}

TEST(PlyPoints, RefusesABadHeaderOrCount) {
  std::vector<PlyPoint> read;
  EXPECT_EQ(ParsePlyPoints("ply\nformat binary_little_endian 1.0\n", "p.ply", &read),
            "p.ply:2: expected 'format ascii 1.0', found 'format binary_little_endian 1.0'");
  std::string text = FormatPlyPoints(std::vector<PlyPoint>{{Vec2(1, 2), 0}}, "c");
  EXPECT_EQ(ParsePlyPoints(text + "3 4 0 0\n", "p.ply", &read),
            "p.ply: the header says 1 vertices, the file has 2");
  read.clear();
  EXPECT_THAT(ParsePlyPoints(text + "3 x 0 0\n", "p.ply", &read), HasSubstr("p.ply:11: field 2"));
  EXPECT_EQ(ParsePlyPoints("ply\n", "p.ply", &read),
            "p.ply: the PLY header ends early (no end_header)");
}

}  // namespace
}  // namespace atlas::formats
