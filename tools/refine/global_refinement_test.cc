#include "tools/refine/global_refinement.h"

#include <gtest/gtest.h>

#include <cmath>

namespace atlas::refine {
namespace {

UncertainPose Edge(double x, double y, double theta, double var_xy, double var_theta) {
  UncertainPose p;
  p.mean = Pose2{x, y, theta};
  p.cov = Vec3(var_xy, var_xy, var_theta).asDiagonal();
  return p;
}

AtlasGraph Frames(int n) {
  AtlasGraph g(8);
  for (int i = 0; i < n; ++i) g.AddFrame(nullptr);
  return g;
}

RefineOptions TightOptions() {
  RefineOptions o;
  o.min_variance = 1e-16;
  return o;
}

// A consistent square loop of four frames (90 degree turns, exact edges, one of them a loop
// closure) and a fifth frame joined to nothing: the refinement keeps the exact arrangement,
// frame 0 at the origin, and leaves the fifth frame out.
TEST(GlobalRefinement, ConsistentLoopIsKeptExactly) {
  AtlasGraph g = Frames(5);
  const double h = M_PI / 2;
  ASSERT_EQ(g.AddEdge(0, 1, Edge(2, 0, h, 0.01, 0.001), EdgeKind::kGenesis), AddEdgeResult::kAdded);
  ASSERT_EQ(g.AddEdge(1, 2, Edge(2, 0, h, 0.01, 0.001), EdgeKind::kGenesis), AddEdgeResult::kAdded);
  ASSERT_EQ(g.AddEdge(2, 3, Edge(2, 0, h, 0.01, 0.001), EdgeKind::kGenesis), AddEdgeResult::kAdded);
  // Frame 0 in frame 3 is (2, 0, +90 deg): stored the other way round (3 in 0) on purpose.
  ASSERT_EQ(g.AddEdge(0, 3, Edge(0, 2, -h, 0.02, 0.002), EdgeKind::kMapMatch),
            AddEdgeResult::kAdded);
  const RefineResult r = RefineGlobal(g, TightOptions());
  ASSERT_EQ(r.status, RefineStatus::kConverged) << r.message;
  EXPECT_EQ(r.frames, 4);
  EXPECT_EQ(r.edges, 4);
  EXPECT_LT(r.final_cost, 1e-12);
  const Pose2 truth[4] = {{0, 0, 0}, {2, 0, h}, {2, 2, M_PI}, {0, 2, -h}};
  for (int f = 0; f < 4; ++f) {
    ASSERT_TRUE(r.refined[f].has_value()) << f;
    EXPECT_NEAR(r.refined[f]->x, truth[f].x, 1e-9) << f;
    EXPECT_NEAR(r.refined[f]->y, truth[f].y, 1e-9) << f;
    EXPECT_NEAR(WrapAngle(r.refined[f]->theta - truth[f].theta), 0.0, 1e-9) << f;
  }
  EXPECT_FALSE(r.refined[4].has_value());
  EXPECT_FALSE(r.initial[4].has_value());
  EXPECT_EQ(r.unreached, 1);
  EXPECT_EQ(r.skipped_edges, 0);
}

// A triangle whose loop does not close: the chain 0-1-2 says frame 2 is at (1, 1) (frame 1 is
// turned by 90 degrees, so the edge 1-2 is measured in rotated coordinates), the direct edge
// 0-2 says (1.3, 0.9). Headings are exact and known almost perfectly, so the positions solve a
// linear weighted least-squares problem with a closed form: the two estimates of frame 2 are
// fused with weights 1/variance (chain variance s01 + s12), and frame 1 takes the share
// s01 / (s01 + s12) of the chain's correction.
TEST(GlobalRefinement, LoopErrorIsSharedByInverseCovariance) {
  const double s01 = 0.01, s12 = 0.03, s02 = 0.02, yaw_var = 1e-12;
  AtlasGraph g = Frames(3);
  const double h = M_PI / 2;
  // Frame 1 at (1, 0, 90 deg); frame 2 at (1, 1, 90 deg) is (1, 0, 0) in frame 1.
  ASSERT_EQ(g.AddEdge(0, 1, Edge(1, 0, h, s01, yaw_var), EdgeKind::kGenesis),
            AddEdgeResult::kAdded);
  ASSERT_EQ(g.AddEdge(1, 2, Edge(1, 0, 0, s12, yaw_var), EdgeKind::kGenesis),
            AddEdgeResult::kAdded);
  ASSERT_EQ(g.AddEdge(0, 2, Edge(1.3, 0.9, h, s02, yaw_var), EdgeKind::kMapMatch),
            AddEdgeResult::kAdded);
  const RefineResult r = RefineGlobal(g, TightOptions());
  ASSERT_EQ(r.status, RefineStatus::kConverged) << r.message;
  const Vec2 chain(1.0, 1.0), direct(1.3, 0.9);
  const double s_chain = s01 + s12;
  const Vec2 x2 = (chain / s_chain + direct / s02) / (1.0 / s_chain + 1.0 / s02);
  const Vec2 x1 = Vec2(1.0, 0.0) + (s01 / s_chain) * (x2 - chain);
  ASSERT_TRUE(r.refined[1] && r.refined[2]);
  EXPECT_NEAR(r.refined[2]->x, x2.x(), 1e-6);
  EXPECT_NEAR(r.refined[2]->y, x2.y(), 1e-6);
  EXPECT_NEAR(r.refined[1]->x, x1.x(), 1e-6);
  EXPECT_NEAR(r.refined[1]->y, x1.y(), 1e-6);
  EXPECT_NEAR(r.refined[1]->theta, h, 1e-6);
  EXPECT_NEAR(r.refined[0]->x, 0.0, 0.0);  // frame 0 is held fixed
  // The initial arrangement is the Dijkstra projection: frame 2 via the direct edge (its
  // determinant is smaller than the chain's).
  ASSERT_TRUE(r.initial[2]);
  EXPECT_NEAR(r.initial[2]->x, 1.3, 1e-12);
  EXPECT_LT(r.final_cost, r.initial_cost);
}

// An edge from frame 0 whose covariance is unusable (negative variances, or singular) is left
// out and counted; the frames it alone joined are reported as not reached, and the solve does
// not touch a frame 0 that has no constraint left (Ceres aborted on setting it constant).
TEST(GlobalRefinement, UnusableCovarianceFromFrameZeroIsLeftOut) {
  for (const double v : {-1.0, 1.0}) {
    AtlasGraph g = Frames(3);
    UncertainPose bad = Edge(1, 0, 0, 0.01, 0.001);
    bad.cov = v < 0 ? Mat3(-Mat3::Identity()) : Mat3(Mat3::Ones());
    ASSERT_EQ(g.AddEdge(0, 1, bad, EdgeKind::kGenesis), AddEdgeResult::kAdded);
    ASSERT_EQ(g.AddEdge(1, 2, Edge(1, 0, 0, 0.01, 0.001), EdgeKind::kGenesis),
              AddEdgeResult::kAdded);
    const RefineResult r = RefineGlobal(g, RefineOptions{});
    EXPECT_EQ(r.status, RefineStatus::kConverged) << v;
    EXPECT_EQ(r.skipped_edges, 1) << v;
    EXPECT_EQ(r.edges, 0) << v;
    EXPECT_EQ(r.frames, 1) << v;
    EXPECT_EQ(r.unreached, 2) << v;
    ASSERT_TRUE(r.refined[0].has_value());
    EXPECT_FALSE(r.refined[1].has_value());
    EXPECT_FALSE(r.refined[2].has_value());
  }
}

// A zero covariance is floored at min_variance (as a near-singular Genesis edge is) and used.
TEST(GlobalRefinement, ZeroCovarianceIsFlooredAndUsed) {
  AtlasGraph g = Frames(2);
  UncertainPose zero = Edge(1, 2, 0.5, 0.0, 0.0);
  ASSERT_EQ(g.AddEdge(0, 1, zero, EdgeKind::kGenesis), AddEdgeResult::kAdded);
  const RefineResult r = RefineGlobal(g, RefineOptions{});
  ASSERT_EQ(r.status, RefineStatus::kConverged) << r.message;
  EXPECT_EQ(r.skipped_edges, 0);
  EXPECT_EQ(r.unreached, 0);
  ASSERT_TRUE(r.refined[1].has_value());
  EXPECT_NEAR(r.refined[1]->x, 1.0, 1e-9);
  EXPECT_NEAR(r.refined[1]->y, 2.0, 1e-9);
}

TEST(GlobalRefinement, EmptyGraphAndBadOptions) {
  AtlasGraph g;
  const RefineResult r = RefineGlobal(g, RefineOptions{});
  EXPECT_EQ(r.status, RefineStatus::kNoFrames);
  EXPECT_TRUE(r.refined.empty());
  RefineOptions bad;
  bad.max_iterations = 0;
  EXPECT_FALSE(bad.Validate().empty());
  EXPECT_TRUE(RefineOptions{}.Validate().empty());
}

}  // namespace
}  // namespace atlas::refine
