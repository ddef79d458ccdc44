#include "core/eval/atlas_relations.h"

#include <gtest/gtest.h>

#include <vector>

namespace atlas::eval {
namespace {

Time AtSeconds(double s) { return FromSeconds(s); }

UncertainPose Edge(const Pose2& mean, double sigma) {
  UncertainPose p;
  p.mean = mean;
  p.cov = Mat3::Identity() * sigma * sigma;
  return p;
}

// Fig. 2's topology: A(0) - B(1), A - C(2), B - D(3), C - D, plus an isolated frame E(4).
// The true frames in the world: A at the origin, B at (5, 0, 0), C at (0, 5, pi/2),
// D at (5, 5, pi/2). The edges through B are exact and certain; the edges through C are
// uncertain and the C -> D edge is off by one metre, so only the path via B (minimum rho) gives
// the true relative pose.
struct Fig2 {
  Pose2 world_a{0, 0, 0}, world_b{5, 0, 0}, world_c{0, 5, 1.5707963267948966},
      world_d{5, 5, 1.5707963267948966}, world_e{20, 0, 0};
  std::vector<EdgeRow> edges;
  explicit Fig2(double sigma_via_b = 0.01, double sigma_via_c = 0.5) {
    edges.push_back({0, 1, Edge(Between(world_a, world_b), sigma_via_b), EdgeKind::kGenesis});
    edges.push_back({0, 2, Edge(Between(world_a, world_c), sigma_via_c), EdgeKind::kGenesis});
    edges.push_back({1, 3, Edge(Between(world_b, world_d), sigma_via_b), EdgeKind::kMapMatch});
    Pose2 wrong = Between(world_c, world_d);
    wrong.x += 1.0;
    edges.push_back({2, 3, Edge(wrong, sigma_via_c), EdgeKind::kMapMatch});
  }
  // The true robot pose `world` written in frame f's coordinates.
  FramePose In(FrameId f, double stamp, const Pose2& world) const {
    const Pose2 frames[] = {world_a, world_b, world_c, world_d, world_e};
    return FramePose{AtSeconds(stamp), f, Between(frames[f], world)};
  }
};

TEST(AtlasRelationsTest, ComposesAlongTheMinimumRhoPath) {
  const Fig2 fig;
  AtlasGraph graph;
  ASSERT_EQ(BuildGraphFromEdges(5, fig.edges, &graph), "");
  const Pose2 r1{1, 1, 0.2}, r2{6, 4, 1.0}, r3{2, 0.5, -0.3}, r4{21, 1, 0};
  std::vector<FramePose> rows = {fig.In(3, 2.0, r2), fig.In(0, 1.0, r1), fig.In(0, 3.0, r3),
                                 fig.In(4, 4.0, r4)};
  DijkstraComposedPoses lookup(rows, graph);
  // Cross-frame A -> D: via B, exact.
  const std::optional<Pose2> d12 = lookup(AtSeconds(1.0), AtSeconds(2.0));
  ASSERT_TRUE(d12.has_value());
  const Pose2 truth12 = Between(r1, r2);
  EXPECT_NEAR(d12->x, truth12.x, 1e-9);
  EXPECT_NEAR(d12->y, truth12.y, 1e-9);
  EXPECT_NEAR(WrapAngle(d12->theta - truth12.theta), 0.0, 1e-9);
  // The reverse direction, D -> A, takes the same path.
  const std::optional<Pose2> d21 = lookup(AtSeconds(2.0), AtSeconds(1.0));
  ASSERT_TRUE(d21.has_value());
  EXPECT_NEAR(Between(r2, r1).x, d21->x, 1e-9);
  EXPECT_NEAR(Between(r2, r1).y, d21->y, 1e-9);
  // Same frame.
  const std::optional<Pose2> d13 = lookup(AtSeconds(1.0), AtSeconds(3.0));
  ASSERT_TRUE(d13.has_value());
  EXPECT_NEAR(d13->x, Between(r1, r3).x, 1e-9);
  // Unconnected frame E, unmatched stamp.
  EXPECT_FALSE(lookup(AtSeconds(1.0), AtSeconds(4.0)).has_value());
  EXPECT_FALSE(lookup(AtSeconds(1.0), AtSeconds(9.0)).has_value());
  EXPECT_EQ(lookup.Counts().cross_frame, 2);
  EXPECT_EQ(lookup.Counts().same_frame, 1);
  EXPECT_EQ(lookup.Counts().unconnected, 1);
  EXPECT_EQ(lookup.Counts().unmatched, 1);
}

TEST(AtlasRelationsTest, SaysHowEachRelationsFramesAreJoined) {
  // Fig. 2 (A-B Genesis, B-D map-match), and a chain of a Genesis and a refined edge beside it:
  // E(4) - F(5) - G(6).
  Fig2 fig;
  fig.edges.push_back({4, 5, Edge(Pose2{5, 0, 0}, 0.01), EdgeKind::kGenesis});
  fig.edges.push_back({5, 6, Edge(Pose2{5, 0, 0}, 0.01), EdgeKind::kRefined});
  AtlasGraph graph;
  ASSERT_EQ(BuildGraphFromEdges(7, fig.edges, &graph), "");
  const Pose2 p{1, 1, 0.2};
  std::vector<FramePose> rows = {{AtSeconds(1.0), 0, p}, {AtSeconds(2.0), 0, p},
                                 {AtSeconds(3.0), 1, p}, {AtSeconds(4.0), 3, p},
                                 {AtSeconds(5.0), 4, p}, {AtSeconds(6.0), 6, p},
                                 {AtSeconds(7.0), 5, p}};
  DijkstraComposedPoses lookup(rows, graph);
  const struct {
    double t1, t2;
    FrameJoin join;
  } cases[] = {{1, 2, FrameJoin::kSameFrame},       {1, 3, FrameJoin::kNeighbours},
               {1, 4, FrameJoin::kThroughMapMatch}, {4, 1, FrameJoin::kThroughMapMatch},
               {3, 4, FrameJoin::kThroughMapMatch}, {5, 6, FrameJoin::kChain},
               {6, 5, FrameJoin::kChain},           {6, 7, FrameJoin::kNeighbours}};
  for (const auto& c : cases) {
    FrameJoin join = FrameJoin::kSameFrame;
    if (c.join == FrameJoin::kSameFrame) join = FrameJoin::kChain;  // must be overwritten
    ASSERT_TRUE(lookup(AtSeconds(c.t1), AtSeconds(c.t2), &join).has_value()) << c.t1 << " " << c.t2;
    EXPECT_EQ(FrameJoinName(join), std::string(FrameJoinName(c.join))) << c.t1 << " " << c.t2;
  }
  EXPECT_EQ(lookup.Counts().same_frame, 1);
  EXPECT_EQ(lookup.Counts().cross_frame, 7);
  EXPECT_EQ(lookup.Counts().neighbours, 2);
  EXPECT_EQ(lookup.Counts().through_map_match, 3);
  EXPECT_EQ(lookup.Counts().chain, 2);
  // Unconnected frames (A and E) have no join.
  FrameJoin untouched = FrameJoin::kChain;
  EXPECT_FALSE(lookup(AtSeconds(1.0), AtSeconds(5.0), &untouched).has_value());
  EXPECT_EQ(untouched, FrameJoin::kChain);
}

TEST(AtlasRelationsTest, TheWrongPathIsTakenWhenItIsTheCertainOne) {
  // Swap the uncertainties: the path via C (with its 1 m error) now has the smaller rho.
  const Fig2 fig(/*sigma_via_b=*/0.5, /*sigma_via_c=*/0.01);
  AtlasGraph graph;
  ASSERT_EQ(BuildGraphFromEdges(5, fig.edges, &graph), "");
  const Pose2 r1{1, 1, 0.2}, r2{6, 4, 1.0};
  DijkstraComposedPoses lookup({fig.In(0, 1.0, r1), fig.In(3, 2.0, r2)}, graph);
  const std::optional<Pose2> d = lookup(AtSeconds(1.0), AtSeconds(2.0));
  ASSERT_TRUE(d.has_value());
  const RelationError e =
      RelationErrorOf(Relation{AtSeconds(1.0), AtSeconds(2.0), Between(r1, r2)}, *d);
  EXPECT_NEAR(e.translation_m, 1.0, 1e-9);
  EXPECT_NEAR(e.rotation_deg, 0.0, 1e-9);
}

TEST(AtlasRelationsTest, BadEdgesAreNamed) {
  AtlasGraph graph;
  const std::vector<EdgeRow> unknown = {{0, 7, Edge(Pose2{}, 0.1), EdgeKind::kGenesis}};
  EXPECT_NE(BuildGraphFromEdges(2, unknown, &graph).find("edge 1"), std::string::npos);
  const std::vector<EdgeRow> twice = {{0, 1, Edge(Pose2{}, 0.1), EdgeKind::kGenesis},
                                      {1, 0, Edge(Pose2{}, 0.1), EdgeKind::kMapMatch}};
  EXPECT_NE(BuildGraphFromEdges(2, twice, &graph).find("edge 2"), std::string::npos);
  const std::vector<EdgeRow> loop = {{1, 1, Edge(Pose2{}, 0.1), EdgeKind::kGenesis}};
  EXPECT_NE(BuildGraphFromEdges(2, loop, &graph).find("itself"), std::string::npos);
}

}  // namespace
}  // namespace atlas::eval
