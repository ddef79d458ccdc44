#include "core/atlas/dijkstra_projection.h"

#include <gtest/gtest.h>

#include "core/testing/fake_local_map.h"

namespace atlas {
namespace {

UncertainPose Edge(double x, double y, double th, double sxy, double sth) {
  return UncertainPose{Pose2{x, y, th}, Vec3(sxy * sxy, sxy * sxy, sth * sth).asDiagonal()};
}

// Fig. 2: A-B, A-C, B-D, C-D. The edges through C are uncertain, so the Dijkstra path from A to
// D goes through B, and from D to A through B as well.
struct Fig2 {
  AtlasGraph graph;
  FrameId a, b, c, d;
  UncertainPose ab, ac, bd, cd;
  Fig2() {
    a = graph.AddFrame(std::make_unique<FakeLocalMap>());
    b = graph.AddFrame(std::make_unique<FakeLocalMap>());
    c = graph.AddFrame(std::make_unique<FakeLocalMap>());
    d = graph.AddFrame(std::make_unique<FakeLocalMap>());
    ab = Edge(10, 0, 0.1, 0.1, 0.01);
    ac = Edge(0, 10, -0.1, 0.5, 0.05);
    bd = Edge(0, 10, 0.05, 0.1, 0.01);
    // C->D stored the other way round (D->C) to exercise the reverse direction.
    cd = Edge(9.5, 0.3, 0.15, 0.5, 0.05);  // pose of D in C
    EXPECT_EQ(graph.AddEdge(a, b, ab, EdgeKind::kGenesis), AddEdgeResult::kAdded);
    EXPECT_EQ(graph.AddEdge(a, c, ac, EdgeKind::kGenesis), AddEdgeResult::kAdded);
    EXPECT_EQ(graph.AddEdge(b, d, bd, EdgeKind::kGenesis), AddEdgeResult::kAdded);
    EXPECT_EQ(graph.AddEdge(d, c, Inverse(cd), EdgeKind::kMapMatch), AddEdgeResult::kAdded);
  }
};

Mat3 ComposedCovByHand(const UncertainPose& x, const UncertainPose& y) {
  // eq. 2 written out with the Jacobians.
  const Mat3 j1 = ComposeJacobianA(x.mean, y.mean);
  const Mat3 j2 = ComposeJacobianB(x.mean);
  return j1 * x.cov * j1.transpose() + j2 * y.cov * j2.transpose();
}

TEST(DijkstraProjection, Fig2FromAGoesThroughB) {
  Fig2 f;
  const Projection p = DijkstraProjection(f.graph, f.a);
  ASSERT_EQ(p.entries.size(), 4u);
  EXPECT_FALSE(p.truncated);
  EXPECT_EQ(p.entries[0].frame, f.a);
  const ProjectedFrame* d = p.Find(f.d);
  ASSERT_NE(d, nullptr);
  EXPECT_EQ(d->parent, f.b);
  EXPECT_EQ(d->hops, 2);
  const Pose2 via_b = Compose(f.ab.mean, f.bd.mean);
  EXPECT_NEAR(d->pose.mean.x, via_b.x, 1e-12);
  EXPECT_NEAR(d->pose.mean.y, via_b.y, 1e-12);
  EXPECT_NEAR(d->pose.mean.theta, via_b.theta, 1e-12);
  const Mat3 cov_b = ComposedCovByHand(f.ab, f.bd);
  EXPECT_LT((d->pose.cov - cov_b).cwiseAbs().maxCoeff(), 1e-12);
  EXPECT_DOUBLE_EQ(d->rho, cov_b.determinant());  // eq. 3
  // The path through C is longer in rho.
  const Mat3 cov_c = ComposedCovByHand(f.ac, f.cd);
  EXPECT_GT(cov_c.determinant(), cov_b.determinant());
  EXPECT_EQ(p.Find(f.c)->parent, f.a);
  EXPECT_EQ(p.Find(f.b)->parent, f.a);
  // Entries are in order of increasing rho.
  for (size_t i = 1; i < p.entries.size(); ++i) EXPECT_LE(p.entries[i - 1].rho, p.entries[i].rho);
}

TEST(DijkstraProjection, Fig2FromDGoesThroughBAndInvertsEdges) {
  Fig2 f;
  const Projection p = DijkstraProjection(f.graph, f.d);
  ASSERT_EQ(p.entries.size(), 4u);
  const ProjectedFrame* a = p.Find(f.a);
  ASSERT_NE(a, nullptr);
  EXPECT_EQ(a->parent, f.b);
  // The pose of A in D is the inverse of D in A along the same path.
  const UncertainPose d_in_a = Compose(f.ab, f.bd);
  const UncertainPose expect = Compose(Inverse(f.bd), Inverse(f.ab));
  EXPECT_NEAR(a->pose.mean.x, Inverse(d_in_a.mean).x, 1e-9);
  EXPECT_NEAR(a->pose.mean.y, Inverse(d_in_a.mean).y, 1e-9);
  EXPECT_LT((a->pose.cov - expect.cov).cwiseAbs().maxCoeff(), 1e-12);
  // C is reached directly over the stored D->C edge: the pose of C in D is the inverse of cd,
  // with covariance J(-) Sigma J(-)^T.
  const ProjectedFrame* c = p.Find(f.c);
  EXPECT_EQ(c->parent, f.d);
  const UncertainPose c_in_d = Inverse(f.cd);
  EXPECT_NEAR(c->pose.mean.x, c_in_d.mean.x, 1e-12);
  EXPECT_NEAR(c->pose.mean.y, c_in_d.mean.y, 1e-12);
  EXPECT_LT((c->pose.cov - c_in_d.cov).cwiseAbs().maxCoeff(), 1e-12);
}

TEST(DijkstraProjection, BoundedProjectionStopsAtLimits) {
  AtlasGraph g;
  FrameId prev = g.AddFrame(std::make_unique<FakeLocalMap>());
  for (int i = 1; i < 200; ++i) {
    const FrameId f = g.AddFrame(std::make_unique<FakeLocalMap>());
    ASSERT_EQ(g.AddEdge(prev, f, Edge(1, 0, 0.01, 0.1, 0.01), EdgeKind::kGenesis),
              AddEdgeResult::kAdded);
    prev = f;
  }
  DijkstraWorkspace ws;
  Projection p;
  ASSERT_TRUE(ws.Project(g, 100, ProjectionLimits{7, 1e300}, &p));
  EXPECT_EQ(p.entries.size(), 7u);
  EXPECT_TRUE(p.truncated);
  // Nearest frames first: 100, then 99/101, ...
  for (const ProjectedFrame& e : p.entries) EXPECT_LE(std::abs(e.frame - 100), 3);
  // A rho bound: only frames whose composed det stays below it.
  const double rho2 = DijkstraProjection(g, 0).Find(2)->rho;
  ASSERT_TRUE(ws.Project(g, 0, ProjectionLimits{1000, rho2}, &p));
  EXPECT_EQ(p.entries.size(), 3u);
  EXPECT_TRUE(p.truncated);
  // Reusing the workspace gives the same answer as a fresh one.
  ASSERT_TRUE(ws.Project(g, 100, ProjectionLimits{7, 1e300}, &p));
  const Projection fresh = DijkstraProjection(g, 100, ProjectionLimits{7, 1e300});
  ASSERT_EQ(fresh.entries.size(), p.entries.size());
  for (size_t i = 0; i < p.entries.size(); ++i)
    EXPECT_EQ(fresh.entries[i].frame, p.entries[i].frame);
  EXPECT_FALSE(ws.Project(g, 500, {}, &p));
}

TEST(AtlasGraph, ReverseEdgeIsInverseWithPropagatedCovariance) {
  AtlasGraph g(2);
  const FrameId a = g.AddFrame(std::make_unique<FakeLocalMap>());
  const FrameId b = g.AddFrame(std::make_unique<FakeLocalMap>());
  const FrameId c = g.AddFrame(std::make_unique<FakeLocalMap>());
  const FrameId d = g.AddFrame(std::make_unique<FakeLocalMap>());
  UncertainPose e = Edge(3, -1, 0.7, 0.2, 0.05);
  e.cov(0, 1) = e.cov(1, 0) = 0.01;
  ASSERT_EQ(g.AddEdge(a, b, e, EdgeKind::kGenesis), AddEdgeResult::kAdded);
  EXPECT_EQ(g.AddEdge(b, a, e, EdgeKind::kMapMatch), AddEdgeResult::kAlreadyAdjacent);
  EXPECT_EQ(g.AddEdge(a, a, e, EdgeKind::kMapMatch), AddEdgeResult::kSameFrame);
  EXPECT_EQ(g.AddEdge(a, 9, e, EdgeKind::kMapMatch), AddEdgeResult::kBadFrame);
  const int idx = g.FindEdge(b, a);
  ASSERT_GE(idx, 0);
  EXPECT_EQ(g.Edge(idx).origin, EdgeKind::kGenesis);
  const UncertainPose back = g.Transform(idx, b);
  const Mat3 j = InverseJacobian(e.mean);
  EXPECT_LT((back.cov - j * e.cov * j.transpose()).cwiseAbs().maxCoeff(), 1e-15);
  const Pose2 id = Compose(g.Transform(idx, a).mean, back.mean);
  EXPECT_NEAR(id.x, 0, 1e-12);
  EXPECT_NEAR(id.theta, 0, 1e-12);
  // Degree bound (max_degree 2): a has one edge, gets a second, a third is refused.
  ASSERT_EQ(g.AddEdge(a, c, e, EdgeKind::kGenesis), AddEdgeResult::kAdded);
  EXPECT_EQ(g.AddEdge(a, d, e, EdgeKind::kMapMatch), AddEdgeResult::kDegreeFull);
  // Refining from the reverse side stores the inverse.
  g.SetTransform(idx, b, Inverse(e), EdgeKind::kRefined, 5);
  EXPECT_EQ(g.Edge(idx).kind, EdgeKind::kRefined);
  EXPECT_EQ(g.Edge(idx).origin, EdgeKind::kGenesis);
  EXPECT_EQ(g.Edge(idx).refined_step, 5);
  EXPECT_NEAR(g.Transform(idx, a).mean.x, e.mean.x, 1e-12);
  EXPECT_LT((g.Transform(idx, a).cov - e.cov).cwiseAbs().maxCoeff(), 1e-12);
}

}  // namespace
}  // namespace atlas
