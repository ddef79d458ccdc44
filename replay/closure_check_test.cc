#include "replay/closure_check.h"

#include <gtest/gtest.h>

#include <cmath>

namespace atlas::replay {
namespace {

UncertainPose Edge(double x, double y, double theta, double sigma_xy, double sigma_theta) {
  UncertainPose p;
  p.mean = Pose2{x, y, theta};
  p.cov = Vec3(sigma_xy * sigma_xy, sigma_xy * sigma_xy, sigma_theta * sigma_theta).asDiagonal();
  return p;
}

// Frame origins in the reference: 0 at (0,0,0), 1 at (5,0,90 deg), 2 at (5,5,180 deg),
// 3 at (0,5,-90 deg). The true pose of 2 in 0 is (5,5,180 deg); of 3 in 1 is (5,5,180 deg) too.
class ClosureCheckTest : public ::testing::Test {
 protected:
  void SetUp() override {
    for (int i = 0; i < 4; ++i) graph_.AddFrame(nullptr);
    ref_ = {Pose2{0, 0, 0}, Pose2{5, 0, M_PI / 2}, Pose2{5, 5, M_PI}, Pose2{0, 5, -M_PI / 2}};
    ASSERT_EQ(graph_.AddEdge(0, 1, Edge(5, 0, M_PI / 2, 0.1, 0.01), EdgeKind::kGenesis),
              AddEdgeResult::kAdded);
  }
  AtlasGraph graph_{8};
  std::vector<std::optional<Pose2>> ref_;
};

TEST_F(ClosureCheckTest, AgreeingMatchPassesAndWrongOneIsFlagged) {
  // 2 in 0: 0.1 m off with sigma 0.1 (d2 = 1): agrees.
  ASSERT_EQ(graph_.AddEdge(0, 2, Edge(5.1, 5.0, M_PI, 0.1, 0.02), EdgeKind::kMapMatch),
            AddEdgeResult::kAdded);
  // 3 in 1: 1 m off with sigma 0.1 (10 sigma): a false closure, and gross (> 0.5 m).
  ASSERT_EQ(graph_.AddEdge(1, 3, Edge(5.0, 4.0, M_PI, 0.1, 0.02), EdgeKind::kMapMatch),
            AddEdgeResult::kAdded);
  const ClosureReport r = CheckClosures(graph_, ref_, ClosureCheckOptions{});
  EXPECT_EQ(r.map_match_edges, 2);  // the Genesis edge is not checked
  ASSERT_EQ(r.edges.size(), 2u);
  EXPECT_NEAR(r.edges[0].d2, 1.0, 1e-6);
  EXPECT_FALSE(r.edges[0].false_chi2);
  EXPECT_FALSE(r.edges[0].false_axis);
  EXPECT_TRUE(r.edges[1].false_chi2);
  EXPECT_TRUE(r.edges[1].false_axis);
  EXPECT_TRUE(r.edges[1].gross);
  EXPECT_NEAR(r.edges[1].d2, 100.0, 1e-4);
  EXPECT_NEAR(r.edges[1].reference.x, 5.0, 1e-12);
  EXPECT_NEAR(r.edges[1].reference.y, 5.0, 1e-12);
  EXPECT_EQ(r.false_chi2, 1);
  EXPECT_EQ(r.gross, 1);
  // One row per checked edge, with a header.
  const std::string text = FormatClosures(r);
  EXPECT_EQ(std::count(text.begin(), text.end(), '\n'), 3);
}

// Per axis and chi-square differ: 2.5 sigma on two axes each is within 3 sigma per axis but
// d2 = 12.5 + small heading error stays under 14.16; 2.9 sigma on all three exceeds chi2.
TEST_F(ClosureCheckTest, ChiSquareAndPerAxisAreDistinct) {
  ASSERT_EQ(graph_.AddEdge(0, 2, Edge(5.0 + 0.29, 5.0 + 0.29, M_PI + 0.029, 0.1, 0.01),
                           EdgeKind::kMapMatch),
            AddEdgeResult::kAdded);
  const ClosureReport r = CheckClosures(graph_, ref_, ClosureCheckOptions{});
  ASSERT_EQ(r.edges.size(), 1u);
  EXPECT_NEAR(r.edges[0].d2, 3 * 2.9 * 2.9, 1e-3);
  EXPECT_TRUE(r.edges[0].false_chi2);
  EXPECT_FALSE(r.edges[0].false_axis);
  EXPECT_FALSE(r.edges[0].gross);
}

TEST_F(ClosureCheckTest, FramesWithoutReferenceAreCountedNotChecked) {
  ref_[3].reset();
  ASSERT_EQ(graph_.AddEdge(1, 3, Edge(5.0, 5.0, M_PI, 0.1, 0.02), EdgeKind::kMapMatch),
            AddEdgeResult::kAdded);
  const ClosureReport r = CheckClosures(graph_, ref_, ClosureCheckOptions{});
  EXPECT_EQ(r.map_match_edges, 1);
  EXPECT_EQ(r.unreferenced, 1);
  EXPECT_TRUE(r.edges.empty());
}

}  // namespace
}  // namespace atlas::replay
