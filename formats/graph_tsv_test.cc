#include "formats/graph_tsv.h"

#include <gtest/gtest.h>

#include <numbers>

namespace atlas::formats {
namespace {

TEST(GraphTsv, RoundTripsAnAtlasGraph) {
  AtlasGraph graph;
  for (int f = 0; f < 3; ++f) graph.AddFrame(nullptr);
  UncertainPose p;
  p.mean = Pose2{1.25, -2.5, 0.75};
  p.cov << 1e-4, 1e-6, 0, 1e-6, 2e-4, 1e-7, 0, 1e-7, 3e-6;
  ASSERT_EQ(graph.AddEdge(0, 1, p, EdgeKind::kGenesis), AddEdgeResult::kAdded);
  p.mean = Pose2{-0.5, 0.125, -3.0};
  ASSERT_EQ(graph.AddEdge(2, 1, p, EdgeKind::kMapMatch), AddEdgeResult::kAdded);
  const std::string text = FormatGraphTsv(graph, "graph: from to x y theta ...");
  EXPECT_EQ(text,
            "# graph: from to x y theta ...\n"
            "0\t1\t1.250000\t-2.500000\t0.750000\t0.0001\t1e-06\t0\t0.0002\t1e-07\t3e-06\tgenesis\n"
            "2\t1\t-0.500000\t0.125000\t-3.000000\t0.0001\t1e-06\t0\t0.0002\t1e-07\t3e-06\t"
            "map-match\n");
  GraphRows rows;
  ASSERT_EQ(ParseGraphTsv(text, "g.tsv", &rows), "");
  ASSERT_EQ(rows.edges.size(), 2u);
  EXPECT_EQ(rows.frame_count, 3);
  EXPECT_EQ(rows.lines, (std::vector<int64_t>{2, 3}));
  EXPECT_EQ(rows.edges[1].from, 2);
  EXPECT_EQ(rows.edges[1].to, 1);
  EXPECT_EQ(rows.edges[1].kind, EdgeKind::kMapMatch);
  EXPECT_EQ(rows.edges[1].to_in_from.mean.y, 0.125);
  EXPECT_EQ(rows.edges[0].to_in_from.cov, graph.Edges()[0].b_in_a.cov);
}

// Every reader of graph.tsv refuses what the atlas graph cannot hold (docs/formats.md).
TEST(GraphTsv, RefusesSelfEdgesRepeatedPairsAndBadCovariances) {
  const std::string ok = "0 1 1 0 0 0.01 0 0 0.01 0 0.001 genesis\n";
  GraphRows rows;
  EXPECT_EQ(ParseGraphTsv("2 2 1 0 0 0.01 0 0 0.01 0 0.001 genesis\n", "g.tsv", &rows),
            "g.tsv:1: edge 2-2 joins a frame to itself");
  rows = {};
  EXPECT_EQ(ParseGraphTsv(ok + "1 0 1 0 0 0.01 0 0 0.01 0 0.001 map-match\n", "g.tsv", &rows),
            "g.tsv:2: edge 1-0 joins two frames that line 1 already joins");
  for (const char* cov : {"0 0 0 0 0 0", "-1 0 0 -1 0 -1", "1 1 1 1 1 1", "1 2 0 1 0 1"}) {
    rows = {};
    const std::string e = ParseGraphTsv(ok + "1 2 1 0 0 " + cov + " genesis\n", "g.tsv", &rows);
    EXPECT_EQ(e.rfind("g.tsv:2: covariance of edge 1-2 is not positive definite", 0), 0u)
        << cov << ": " << e;
  }
  rows = {};
  EXPECT_EQ(ParseGraphTsv("0 1 1 2 0 1 0 0 1 0 1 teleport\n", "g.tsv", &rows),
            "g.tsv:1: field 12 is 'teleport', not an edge kind (genesis, map-match, refined)");
  EXPECT_EQ(ParseGraphTsv("0 1 1e308 2 0 1 0 0 1 0 1 genesis\n", "g.tsv", &rows)
                .rfind("g.tsv:1: field 3 is 1e+308, out of range for a position", 0),
            0u);
  EXPECT_EQ(
      ParseGraphTsv("# h\n0 1 1 2\n", "g.tsv", &rows).rfind("g.tsv:2: expected 12 fields (", 0),
      0u);
  rows = {};
  ASSERT_EQ(ParseGraphTsv("0 1 1 0 7.0 0.01 0 0 0.01 0 0.001 refined\n", "g.tsv", &rows), "");
  EXPECT_NEAR(rows.edges[0].to_in_from.mean.theta, 7.0 - 2 * std::numbers::pi, 1e-12);
}

}  // namespace
}  // namespace atlas::formats
