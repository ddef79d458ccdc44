#include "core/atlas/atlas.h"

#include <gtest/gtest.h>

#include <cstdio>
#include <cstdlib>
#include <set>

#include "core/atlas/atlas_test_world.h"

namespace atlas {
namespace {

// Checks the invariants every step must keep.
void CheckInvariants(const Atlas& atlas) {
  const auto& hs = atlas.Hypotheses();
  const AtlasOptions& o = atlas.Options();
  ASSERT_LE(static_cast<int>(hs.size()), o.max_hypotheses);
  std::set<FrameId> frames;
  int dominant = 0;
  for (const Hypothesis& h : hs) {
    EXPECT_TRUE(frames.insert(h.frame).second) << "two hypotheses in frame " << h.frame;
    EXPECT_NE(h.state, HypothesisState::kRetired);
    dominant += h.dominant;
    if (h.dominant) {
      EXPECT_EQ(h.state, HypothesisState::kMature);
    }
  }
  EXPECT_LE(dominant, 1);
  const StepStats& s = atlas.LastStats();
  EXPECT_LE(s.frames_examined, o.projection_max_frames);
  EXPECT_LE(s.candidates_matched, o.match_candidates_per_step);
  EXPECT_LE(s.seeded, o.max_seeds_per_step);
  EXPECT_LE(s.refined, o.max_refinements_per_step);
  for (FrameId f = 0; f < atlas.Graph().FrameCount(); ++f)
    EXPECT_LE(static_cast<int>(atlas.Graph().Frame(f).edges.size()), o.max_degree);
}

TEST(Atlas, OptionsValidate) {
  EXPECT_EQ(AtlasOptions{}.Validate(), "");
  AtlasOptions o;
  o.max_hypotheses = 1;
  EXPECT_NE(o.Validate(), "");
  o = AtlasOptions{};
  o.lifecycle.probation_scans = 1;
  EXPECT_NE(o.Validate(), "");
  o = AtlasOptions{};
  o.min_match_lines = 1;
  EXPECT_NE(o.Validate(), "");
}

TEST(Atlas, FirstStepMakesFrameZeroWithMatureDominantHypothesis) {
  TestWorld w;
  Atlas atlas(TestWorld::Options(), w.Factory(), std::make_shared<FakeBootstrapper>());
  atlas.Step(Pose2{}, TestScan());
  ASSERT_EQ(atlas.Graph().FrameCount(), 1);
  const DominantOutput d = atlas.Dominant();
  ASSERT_TRUE(d.valid);
  EXPECT_EQ(d.frame, 0);
  EXPECT_EQ(d.pose.mean.x, 0.0);
  CheckInvariants(atlas);
}

// III-C: the Genesis edge is the robot pose in the old frame with exactly its covariance; the
// robot is at exactly zero with zero covariance in the new frame.
TEST(Atlas, GenesisEdgeCarriesRobotCovarianceExactly) {
  TestWorld w;
  Atlas atlas(TestWorld::Options(), w.Factory(), std::make_shared<FakeBootstrapper>());
  bool saw_genesis = false;
  for (int i = 0; i < 80 && !saw_genesis; ++i) {
    const StepStats& s = atlas.Step(Pose2{0.25, 0.0, 0.01}, TestScan());
    CheckInvariants(atlas);
    if (s.genesis == 0) continue;
    saw_genesis = true;
    const AtlasGraph& g = atlas.Graph();
    ASSERT_EQ(g.FrameCount(), 2);
    const AtlasEdge& e = g.Edge(g.EdgeCount() - 1);
    EXPECT_EQ(e.kind, EdgeKind::kGenesis);
    EXPECT_EQ(e.a, 0);
    EXPECT_EQ(e.b, 1);
    // The old map is not updated after Genesis within the step: its pose is the one used.
    const UncertainPose robot = g.Frame(0).map->RobotPose();
    EXPECT_EQ(e.b_in_a.mean.x, robot.mean.x);
    EXPECT_EQ(e.b_in_a.mean.y, robot.mean.y);
    EXPECT_EQ(e.b_in_a.mean.theta, robot.mean.theta);
    for (int k = 0; k < 9; ++k) EXPECT_EQ(e.b_in_a.cov.data()[k], robot.cov.data()[k]) << k;
    EXPECT_GT(robot.cov.determinant(), 0.0);  // a real covariance was carried
    const UncertainPose fresh = g.Frame(1).map->RobotPose();
    EXPECT_EQ(fresh.mean.x, 0.0);
    EXPECT_EQ(fresh.mean.y, 0.0);
    EXPECT_EQ(fresh.mean.theta, 0.0);
    EXPECT_TRUE(fresh.cov.isZero(0.0));
    const DominantOutput d = atlas.Dominant();
    ASSERT_TRUE(d.valid);
    // At capacity the old hypothesis stays mature (it fails later, as the robot leaves); the
    // new frame carries a mature hypothesis of its own.
    bool new_frame_mature = false;
    for (const Hypothesis& h : atlas.Hypotheses())
      new_frame_mature |= h.frame == 1 && h.state == HypothesisState::kMature;
    EXPECT_TRUE(new_frame_mature);
  }
  EXPECT_TRUE(saw_genesis);
}

// Out and back along a corridor: Genesis on the way out, traversal on the way back, and the
// dominant frame id falls back to 0 (Fig. 7).
TEST(Atlas, TraversalFallsBackToKnownFrames) {
  TestWorld w;
  Atlas atlas(TestWorld::Options(), w.Factory(), std::make_shared<FakeBootstrapper>());
  std::vector<FrameId> dominant;
  int matured = 0, refined = 0, seeded = 0;
  for (int i = 0; i < 120; ++i) {
    const double v = i < 60 ? 0.25 : -0.25;
    const StepStats& s = atlas.Step(Pose2{v, 0.0, 0.0}, TestScan());
    CheckInvariants(atlas);
    dominant.push_back(s.dominant_frame);
    if (getenv("ATLAS_TRACE")) {
      printf("%3d dom %2d frames %2d seed %d mat %d del %d ret %d gen %d |", i, s.dominant_frame,
             s.frames, s.seeded, s.matured, s.deleted, s.retired, s.genesis);
      for (const Hypothesis& h : atlas.Hypotheses())
        printf(" [%d %s q%.2f x%.2f]", h.frame, HypothesisStateName(h.state), h.q,
               atlas.PoseOf(h).mean.x);
      printf("\n");
    }
    matured += s.matured;
    refined += s.refined;
    seeded += s.seeded;
  }
  const int frames = atlas.Graph().FrameCount();
  EXPECT_GE(frames, 3);
  const FrameId peak = *std::max_element(dominant.begin(), dominant.end());
  EXPECT_EQ(peak, frames - 1);
  EXPECT_EQ(dominant.back(), 0) << "the robot is back at the start: frame 0 should dominate";
  EXPECT_GT(seeded, 0);
  EXPECT_GE(matured, 1);
  EXPECT_GE(refined, 1);
  bool any_refined = false;
  for (const AtlasEdge& e : atlas.Graph().Edges()) any_refined |= e.kind == EdgeKind::kRefined;
  EXPECT_TRUE(any_refined);
  // No new frames were made on the way back: known frames were reused.
  EXPECT_LE(frames, 1 + static_cast<int>(60 * 0.25 / 1.0));
}

TEST(Atlas, JuvenileKilledWhenBootstrapFailsAndNeverExtendsItsMap) {
  TestWorld w;
  auto never = std::make_shared<FakeBootstrapper>(1 << 30);
  Atlas atlas(TestWorld::Options(), w.Factory(), never);
  int killed = 0, matured = 0;
  for (int i = 0; i < 120; ++i) {
    const double v = i < 60 ? 0.25 : -0.25;
    std::vector<int> complexity(atlas.Graph().FrameCount());
    for (FrameId f = 0; f < atlas.Graph().FrameCount(); ++f)
      complexity[f] = atlas.Graph().Frame(f).map->Complexity();
    const StepStats& s = atlas.Step(Pose2{v, 0.0, 0.0}, TestScan());
    CheckInvariants(atlas);
    killed += s.killed_by_w;
    matured += s.matured;
    for (const Hypothesis& h : atlas.Hypotheses()) {
      if (h.state != HypothesisState::kJuvenile || h.steps == 0) continue;
      const auto* trial = dynamic_cast<const FakeLocalMap*>(h.trial_map.get());
      ASSERT_NE(trial, nullptr);
      EXPECT_FALSE(trial->last_allow_new());
      EXPECT_EQ(trial->Complexity(), complexity[h.frame]);
      EXPECT_EQ(atlas.Graph().Frame(h.frame).map->Complexity(), complexity[h.frame]);
    }
  }
  EXPECT_GT(killed, 0);
  EXPECT_EQ(matured, 0);
  EXPECT_GT(never->calls(), 0);
}

TEST(Atlas, WorkPerStepIsBoundedOnALongRun) {
  TestWorld w;
  w.radius = 1.0;
  w.capacity = 4;
  w.Install();
  AtlasOptions o = TestWorld::Options();
  o.projection_max_frames = 8;
  Atlas atlas(o, w.Factory(), std::make_shared<FakeBootstrapper>());
  for (int i = 0; i < 3000; ++i) {
    const double turn = (i / 200) % 2 ? 0.02 : -0.02;
    atlas.Step(Pose2{0.25, 0.0, turn}, TestScan());
    CheckInvariants(atlas);
    if (HasFatalFailure()) return;
  }
  EXPECT_GT(atlas.Graph().FrameCount(), 100);
}

TEST(Atlas, SerializeRoundTripsAndRejectsGarbage) {
  TestWorld w;
  Atlas a(TestWorld::Options(), w.Factory(), std::make_shared<FakeBootstrapper>());
  for (int i = 0; i < 75; ++i) a.Step(Pose2{i < 60 ? 0.25 : -0.25, 0.0, 0.0}, TestScan());
  const std::string image = a.Serialize();
  Atlas b(TestWorld::Options(), w.Factory(), std::make_shared<FakeBootstrapper>());
  ASSERT_TRUE(b.Deserialize(image));
  EXPECT_TRUE(b.Serialize() == image);
  EXPECT_EQ(b.Graph().FrameCount(), a.Graph().FrameCount());
  EXPECT_EQ(b.Hypotheses().size(), a.Hypotheses().size());
  for (int i = 0; i < 30; ++i) {
    const StepStats sa = a.Step(Pose2{-0.25, 0.0, 0.0}, TestScan());
    const StepStats sb = b.Step(Pose2{-0.25, 0.0, 0.0}, TestScan());
    EXPECT_EQ(sa.dominant_frame, sb.dominant_frame);
    EXPECT_EQ(sa.hypotheses_alive, sb.hypotheses_alive);
    EXPECT_EQ(a.Dominant().pose.mean.x, b.Dominant().pose.mean.x);
  }
  // Truncations and flipped bytes are rejected and leave the atlas as it was.
  Atlas c(TestWorld::Options(), w.Factory(), std::make_shared<FakeBootstrapper>());
  c.Step(Pose2{}, TestScan());
  const std::string before = c.Serialize();
  for (size_t n : {size_t{0}, size_t{3}, image.size() / 2, image.size() - 1})
    EXPECT_FALSE(c.Deserialize(image.substr(0, n))) << n;
  std::string bad = image;
  bad[4] ^= 0x7f;  // version
  EXPECT_FALSE(c.Deserialize(bad));
  EXPECT_FALSE(c.Deserialize(image + "x"));
  EXPECT_TRUE(c.Serialize() == before);
}

}  // namespace
}  // namespace atlas
