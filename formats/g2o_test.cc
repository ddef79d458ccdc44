#include "formats/g2o.h"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

namespace atlas::formats {
namespace {

using ::testing::HasSubstr;

G2oGraph TwoFrames() {
  G2oGraph g;
  g.vertices = {{0, Pose2{0, 0, 0}}, {1, Pose2{2.5, -1.0, 0.75}}};
  Mat3 cov;
  cov << 0.04, 0.001, 0.0, 0.001, 0.09, 0.002, 0.0, 0.002, 0.01;
  G2oEdge e{0, 1, Pose2{2.5, -1.0, 0.75}, Mat3::Identity()};
  EXPECT_TRUE(InformationOf(cov, &e.information));
  g.edges = {e};
  g.fixed = {0};
  return g;
}

TEST(G2o, InformationIsTheInverseCovariance) {
  Mat3 cov;
  cov << 0.04, 0.001, 0.0, 0.001, 0.09, 0.002, 0.0, 0.002, 0.01;
  Mat3 info;
  ASSERT_TRUE(InformationOf(cov, &info));
  EXPECT_TRUE((info * cov).isApprox(Mat3::Identity(), 1e-12));
  EXPECT_NEAR(info(0, 0), 1 / 0.04, 0.1);
  Mat3 singular = Mat3::Ones();
  EXPECT_FALSE(InformationOf(singular, &info));
}

TEST(G2o, WrittenThenReadBack) {
  const G2oGraph g = TwoFrames();
  const std::string text = FormatG2o(g, "test graph");
  EXPECT_THAT(text, HasSubstr("VERTEX_SE2 1 2.500000 -1.000000 0.750000\n"));
  EXPECT_THAT(text, HasSubstr("EDGE_SE2 0 1 2.500000 -1.000000 0.750000 "));
  EXPECT_THAT(text, HasSubstr("\nFIX 0\n"));
  G2oGraph read;
  ASSERT_EQ(ParseG2o(text, "a.g2o", &read), "");
  ASSERT_EQ(read.vertices.size(), 2u);
  EXPECT_EQ(read.vertices[1].id, 1);
  EXPECT_DOUBLE_EQ(read.vertices[1].pose.theta, 0.75);
  ASSERT_EQ(read.edges.size(), 1u);
  EXPECT_EQ(read.edges[0].from, 0);
  EXPECT_EQ(read.edges[0].to, 1);
  EXPECT_DOUBLE_EQ(read.edges[0].measurement.x, 2.5);
  // %.9g keeps the information to 9 significant digits, in g2o's upper-triangle order.
  EXPECT_TRUE(read.edges[0].information.isApprox(g.edges[0].information, 1e-8));
  EXPECT_EQ(read.fixed, std::vector<int>{0});
  EXPECT_EQ(FormatG2o(read, "test graph"), text);
}

TEST(G2o, RefusesWhatIsNotAnSe2GraphNamingTheLine) {
  G2oGraph g;
  EXPECT_EQ(ParseG2o("VERTEX_SE2 0 0 0 0\nVERTEX_XY 1 0 0\n", "a.g2o", &g),
            "a.g2o:2: tag 'VERTEX_XY' is not VERTEX_SE2, EDGE_SE2 or FIX");
  g = {};
  EXPECT_THAT(ParseG2o("VERTEX_SE2 0 0 0\n", "a.g2o", &g),
              HasSubstr("a.g2o:1: expected 5 fields (VERTEX_SE2 id x y theta), found 4"));
  g = {};
  EXPECT_EQ(ParseG2o("VERTEX_SE2 0 0 0 0\nVERTEX_SE2 0 1 0 0\n", "a.g2o", &g),
            "a.g2o:2: vertex 0 given twice");
  g = {};
  EXPECT_THAT(ParseG2o("VERTEX_SE2 0 0 0 0\nEDGE_SE2 0 3 1 0 0 1 0 0 1 0 1\n", "a.g2o", &g),
              HasSubstr("a.g2o:2: field 3 names vertex 3"));
  g = {};
  EXPECT_THAT(ParseG2o("VERTEX_SE2 0 0 0 0\nVERTEX_SE2 1 0 0 0\nEDGE_SE2 0 1 1 0 0 1 0 0 -1 0 1\n",
                       "a.g2o", &g),
              HasSubstr("a.g2o:3: the information matrix of edge 0-1"));
  g = {};
  EXPECT_THAT(ParseG2o("VERTEX_SE2 0 0 x 0\n", "a.g2o", &g), HasSubstr("a.g2o:1: field 4"));
}

}  // namespace
}  // namespace atlas::formats
