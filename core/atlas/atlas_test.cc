#include "core/atlas/atlas.h"

#include <gtest/gtest.h>

#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <functional>
#include <limits>
#include <numbers>
#include <set>
#include <vector>

#include "core/atlas/dijkstra_projection.h"
#include "core/testing/atlas_test_world.h"

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
  // Self-matches are searches of the same budget: never a self-match of each map and a
  // cross-match in one step.
  EXPECT_LE(s.candidates_matched + s.match_unconnected + s.self_matches,
            o.match_candidates_per_step + o.resume_candidates_per_step);
  EXPECT_LE(s.seeded, o.max_seeds_per_step);
  EXPECT_LE(s.refined, o.max_refinements_per_step);
  for (FrameId f = 0; f < atlas.Graph().FrameCount(); ++f)
    EXPECT_LE(static_cast<int>(atlas.Graph().Frame(f).edges.size()), o.max_degree);
}

TEST(Atlas, OptionsValidate) {
  EXPECT_EQ(AtlasOptions{}.Validate(), "");
  const std::vector<std::function<void(AtlasOptions&)>> invalid = {
      [](AtlasOptions& o) { o.max_hypotheses = 1; },
      [](AtlasOptions& o) { o.lifecycle.probation_scans = 1; },
      [](AtlasOptions& o) { o.min_match_lines = 1; },
      [](AtlasOptions& o) { o.genesis_cov_scale = 0.5; },
      [](AtlasOptions& o) { o.return_q = 1.5; },
      [](AtlasOptions& o) { o.return_radius = 0.0; },
      [](AtlasOptions& o) { o.return_far_radius = -1.0; },
      [](AtlasOptions& o) { o.return_far_radius = o.return_radius + 1.0; },
  };
  for (size_t i = 0; i < invalid.size(); ++i) {
    AtlasOptions o;
    invalid[i](o);
    EXPECT_NE(o.Validate(), "") << "case " << i;
  }
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

// Dominant().switched marks exactly the steps at which another hypothesis dominates than at the
// step before (a Genesis hands the robot to the new frame's hypothesis), so that a consumer can
// tell a switch from motion.
TEST(Atlas, SwitchedMarksExactlyTheStepsWhereTheDominantHypothesisChanges) {
  TestWorld w;
  Atlas atlas(TestWorld::Options(), w.Factory(), std::make_shared<FakeBootstrapper>());
  atlas.Step(Pose2{}, TestScan());
  EXPECT_FALSE(atlas.Dominant().switched);  // the first step has no previous dominant
  int64_t previous = atlas.Dominant().hypothesis;
  int switches = 0;
  for (int i = 0; i < 200; ++i) {
    atlas.Step(Pose2{0.25, 0.0, 0.01}, TestScan());
    const DominantOutput d = atlas.Dominant();
    ASSERT_TRUE(d.valid);
    EXPECT_EQ(d.switched, d.hypothesis != previous) << "step " << i;
    switches += d.switched;
    previous = d.hypothesis;
  }
  EXPECT_GT(switches, 0) << "the test world made no switch";
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

// genesis_cov_scale multiplies the covariance the Genesis edge takes from the robot, and nothing
// else: the same run with scale 1 and 2 makes the same edge mean and twice its covariance.
TEST(Atlas, GenesisCovarianceScaleMultipliesOnlyTheEdgeCovariance) {
  TestWorld w1, w2;
  AtlasOptions o = TestWorld::Options();
  Atlas plain(o, w1.Factory(), std::make_shared<FakeBootstrapper>());
  o.genesis_cov_scale = 2.0;
  Atlas scaled(o, w2.Factory(), std::make_shared<FakeBootstrapper>());
  bool saw_genesis = false;
  for (int i = 0; i < 80 && !saw_genesis; ++i) {
    const int a = plain.Step(Pose2{0.25, 0.0, 0.01}, TestScan()).genesis;
    const int b = scaled.Step(Pose2{0.25, 0.0, 0.01}, TestScan()).genesis;
    ASSERT_EQ(a, b);
    if (a == 0) continue;
    saw_genesis = true;
    const AtlasEdge& ep = plain.Graph().Edge(plain.Graph().EdgeCount() - 1);
    const AtlasEdge& es = scaled.Graph().Edge(scaled.Graph().EdgeCount() - 1);
    ASSERT_EQ(es.kind, EdgeKind::kGenesis);
    EXPECT_EQ(es.b_in_a.mean.x, ep.b_in_a.mean.x);
    EXPECT_EQ(es.b_in_a.mean.y, ep.b_in_a.mean.y);
    EXPECT_EQ(es.b_in_a.mean.theta, ep.b_in_a.mean.theta);
    ASSERT_GT(ep.b_in_a.cov.trace(), 0.0);
    EXPECT_TRUE(es.b_in_a.cov.isApprox(Mat3(2.0 * ep.b_in_a.cov), 1e-12));
    EXPECT_TRUE(scaled.Graph().Frame(1).map->RobotPose().cov.isZero(0.0));
  }
  EXPECT_TRUE(saw_genesis);
}

// Traversal where the robot returns: with return_q above q_traverse, a dominant q in
// [q_traverse, return_q) seeds too, but only frames whose origin lies within return_radius of
// the seed. Out and back along the corridor: with a radius no seed can meet (1 mm), the run is
// step for step the run without the band; with a radius every seed meets, the band seeds at
// steps where the plain run does not.
TEST(Atlas, ReturnBandSeedsOnlyFramesWhoseOriginIsNear) {
  auto run = [](double return_q, double radius) {
    TestWorld w;
    AtlasOptions o = TestWorld::Options();
    o.return_q = return_q;
    o.return_radius = radius;
    Atlas atlas(o, w.Factory(), std::make_shared<FakeBootstrapper>());
    std::vector<std::pair<int, FrameId>> steps;
    for (int i = 0; i < 120; ++i) {
      const StepStats& s = atlas.Step(Pose2{i < 60 ? 0.25 : -0.25, 0.0, 0.0}, TestScan());
      CheckInvariants(atlas);
      steps.emplace_back(s.seeded, s.dominant_frame);
    }
    return steps;
  };
  const auto plain = run(0.0, 4.0);
  EXPECT_EQ(run(0.99, 1e-3), plain);
  const auto band = run(0.99, 1e9);
  int extra = 0;
  for (size_t i = 0; i < plain.size() && i < band.size(); ++i)
    extra += band[i].first > 0 && plain[i].first == 0;
  EXPECT_GT(extra, 0) << "the band never seeded where the plain run did not";
}

// The return band beyond traversal_max_hops: frames farther along the graph are seeded only
// with return_far_radius, only within it (a 1 mm radius gives exactly the run without it),
// and they are then seeded (a huge radius, here with traversal_max_hops 1).
TEST(Atlas, ReturnBandSeedsFramesBeyondTheHopsOnlyWithinTheFarRadius) {
  struct Run {
    std::vector<std::pair<int, FrameId>> steps;
    int far_seeds = 0;
  };
  auto run = [](double far_radius) {
    TestWorld w;
    AtlasOptions o = TestWorld::Options();
    o.return_q = 0.99;
    o.return_radius = 1e9;
    o.return_far_radius = far_radius;
    o.traversal_max_hops = 1;
    Atlas atlas(o, w.Factory(), std::make_shared<FakeBootstrapper>());
    Run r;
    for (int i = 0; i < 160; ++i) {
      const StepStats& s = atlas.Step(Pose2{i < 80 ? 0.25 : -0.25, 0.0, 0.0}, TestScan());
      CheckInvariants(atlas);
      r.steps.emplace_back(s.seeded, s.dominant_frame);
      for (const Hypothesis& h : atlas.Hypotheses()) {
        if (h.state != HypothesisState::kJuvenile || h.born_step != s.step) continue;
        // Hops as traversal counts them: along the Dijkstra projection from a mature frame.
        int nearest = -1;
        for (const Hypothesis& m : atlas.Hypotheses()) {
          if (m.state != HypothesisState::kMature) continue;
          const Projection p = DijkstraProjection(atlas.Graph(), m.frame);
          const ProjectedFrame* e = p.Find(h.frame);
          if (e != nullptr && (nearest < 0 || e->hops < nearest)) nearest = e->hops;
        }
        r.far_seeds += nearest > o.traversal_max_hops;
      }
    }
    return r;
  };
  const Run off = run(0.0);
  EXPECT_EQ(off.far_seeds, 0);
  EXPECT_EQ(run(1e-3).steps, off.steps);
  const Run far = run(1e9);
  EXPECT_GT(far.far_seeds, 0) << "no frame beyond traversal_max_hops was seeded";
  EXPECT_NE(far.steps, off.steps);
}

// Two mature hypotheses in adjacent frames must agree with the edge between them (edge
// refinement's gate). Right after Genesis the old frame's hypothesis is still the dominant one
// (the new map has no lines yet). The new frame's hypothesis is made to jump 3 m sideways (a
// wrong association): it contradicts the dominant one across the Genesis edge and is retired in
// that step, and the edge is not refined towards it. Without the jump it stays.
TEST(Atlas, MatureHypothesisContradictingTheDominantAcrossAnEdgeIsRetired) {
  for (const bool jump : {false, true}) {
    SCOPED_TRACE(jump ? "frame 1 jumps" : "no jump");
    TestWorld w;
    Atlas atlas(TestWorld::Options(), w.Factory(), std::make_shared<FakeBootstrapper>());
    const auto alive_in = [&atlas](FrameId f) {
      for (const Hypothesis& h : atlas.Hypotheses())
        if (h.frame == f) return true;
      return false;
    };
    int genesis_step = -1;
    for (int i = 0; i < 80 && genesis_step < 0; ++i)
      if (atlas.Step(Pose2{0.25, 0.0, 0.0}, TestScan()).genesis > 0) genesis_step = i;
    ASSERT_GE(genesis_step, 0) << "no Genesis: the test world changed";
    ASSERT_TRUE(alive_in(0) && alive_in(1));
    ASSERT_EQ(atlas.Dominant().frame, 0) << "the test world changed";
    if (jump) {
      auto once = std::make_shared<bool>(true);
      w.script->relocate = [once](int tag, const Pose2& p) {
        if (tag != 1 || !*once) return p;
        *once = false;
        return Pose2{p.x, p.y + 3.0, p.theta};
      };
    }
    const StepStats& s = atlas.Step(Pose2{0.25, 0.0, 0.0}, TestScan());
    CheckInvariants(atlas);
    const AtlasGraph& g = atlas.Graph();
    const AtlasEdge& e = g.Edge(g.FindEdge(0, 1));
    EXPECT_LT(std::abs(e.b_in_a.mean.y), 0.5) << "the edge moved towards the jumped hypothesis";
    EXPECT_TRUE(alive_in(0));
    EXPECT_EQ(s.contradicting, jump ? 1 : 0);
    EXPECT_EQ(alive_in(1), !jump);
  }
}

// Edge refinement (III-F) leaves map-match edges alone unless asked: the Genesis edge of a fresh
// frame is relabelled as made by map-matching in the byte image (kind and origin follow the
// edge's 12 doubles there; no juvenile is alive, so no later copy of them), and with both
// hypotheses mature the edge is refined only with refine_map_match_edges. The Genesis edge
// itself is refined either way.
TEST(Atlas, MapMatchEdgesAreRefinedOnlyWhenAsked) {
  for (const bool refine_mm : {false, true}) {
    for (const bool relabel : {false, true}) {
      SCOPED_TRACE(std::string(refine_mm ? "refine_map_match_edges" : "default") +
                   (relabel ? ", map-match edge" : ", Genesis edge"));
      TestWorld w;
      AtlasOptions o = TestWorld::Options();
      o.refine_map_match_edges = refine_mm;
      Atlas atlas(o, w.Factory(), std::make_shared<FakeBootstrapper>());
      int i = 0;
      while (i < 80 && atlas.Step(Pose2{0.25, 0.0, 0.0}, TestScan()).genesis == 0) ++i;
      ASSERT_EQ(atlas.Graph().EdgeCount(), 1) << "no Genesis: the test world changed";
      std::string image = atlas.Serialize();
      if (relabel) {
        const AtlasEdge& e = atlas.Graph().Edge(0);
        const double mean[3] = {e.b_in_a.mean.x, e.b_in_a.mean.y, e.b_in_a.mean.theta};
        // The last copy: frame 0's map blob, written before the edges, holds the same pose.
        const size_t at = image.rfind(std::string(reinterpret_cast<const char*>(mean), 24));
        ASSERT_NE(at, std::string::npos);
        image[at + 96] = static_cast<char>(EdgeKind::kMapMatch);  // kind, after mean and cov
        image[at + 97] = static_cast<char>(EdgeKind::kMapMatch);  // origin
      }
      Atlas restored(o, w.Factory(), std::make_shared<FakeBootstrapper>());
      ASSERT_TRUE(restored.Deserialize(image));
      ASSERT_EQ(restored.Graph().Edge(0).origin,
                relabel ? EdgeKind::kMapMatch : EdgeKind::kGenesis);
      int refined = 0, both_mature = 0;
      for (int k = 0; k < 8; ++k) {
        refined += restored.Step(Pose2{0.25, 0.0, 0.0}, TestScan()).refined;
        both_mature += restored.Hypotheses().size() == 2;
      }
      ASSERT_GE(both_mature, 3)
          << "the old frame's hypothesis did not stay: the test world changed";
      if (relabel && !refine_mm) {
        EXPECT_EQ(refined, 0);
        EXPECT_EQ(restored.Graph().Edge(0).refined_step, -1);
      } else {
        EXPECT_GE(refined, 1);
        EXPECT_EQ(restored.Graph().Edge(0).kind, EdgeKind::kRefined);
      }
    }
  }
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

TEST(Atlas, UndeterminedJuvenileAccumulatesUntilProbationThenIsKilled) {
  TestWorld w;
  auto undetermined = std::make_shared<FakeBootstrapper>(1 << 30, BootstrapOutcome::kUndetermined);
  const AtlasOptions o = TestWorld::Options();
  Atlas atlas(o, w.Factory(), undetermined);
  int killed = 0, matured = 0, seeded = 0;
  for (int i = 0; i < 120; ++i) {
    const double v = i < 60 ? 0.25 : -0.25;
    const StepStats& s = atlas.Step(Pose2{v, 0.0, 0.0}, TestScan());
    CheckInvariants(atlas);
    seeded += s.seeded;
    killed += s.killed_by_w;
    matured += s.matured;
    // Z grows by one step per step once w is undetermined.
    for (const Hypothesis& h : atlas.Hypotheses()) {
      if (h.state != HypothesisState::kJuvenile) continue;
      EXPECT_FALSE(h.bootstrapped);
      EXPECT_EQ(static_cast<int>(h.z.size()), h.steps);
      EXPECT_LT(h.steps, o.lifecycle.probation_scans);
    }
  }
  ASSERT_GT(seeded, 0);
  EXPECT_GT(killed, 0);
  EXPECT_EQ(matured, 0);
  // w was tried on every Z from bootstrap_scans to the end of probation.
  EXPECT_EQ(undetermined->max_z(), o.lifecycle.probation_scans);
}

// w solved in `slices` steps (PoseBootstrapper::Begin): the solution is the juvenile's pose at
// Begin moved 0.5 m along the frame's x axis.
class SlicedBootstrapper : public PoseBootstrapper {
 public:
  explicit SlicedBootstrapper(int slices) : slices_(slices) {}
  PoseBootstrap Solve(const LocalMap&, const LocalMap&, const std::vector<JuvenileScan>&,
                      const UncertainPose&) const override {
    ADD_FAILURE() << "the atlas solves w through Begin";
    return {};
  }
  std::unique_ptr<BootstrapSearch> Begin(const LocalMap& map, const LocalMap&,
                                         const std::vector<JuvenileScan>&,
                                         const UncertainPose&) const override {
    return std::make_unique<Search>(this, map.RobotPose().mean);
  }
  mutable int continues = 0;  // Continue calls (the test resets it every step)
  mutable Pose2 last_now;     // the juvenile's pose when the last search finished

 private:
  class Search : public BootstrapSearch {
   public:
    Search(const SlicedBootstrapper* w, const Pose2& begin) : w_(w), begin_(begin) {}
    bool Continue(const LocalMap& map, const LocalMap&, const std::vector<JuvenileScan>&) override {
      ++w_->continues;
      if (++slices_ < w_->slices_) return false;
      w_->last_now = map.RobotPose().mean;
      return true;
    }
    PoseBootstrap TakeResult() override {
      PoseBootstrap r;
      r.outcome = BootstrapOutcome::kSolved;
      r.pose =
          UncertainPose{Pose2{begin_.x + 0.5, begin_.y, begin_.theta}, Mat3::Identity() * 1e-4};
      return r;
    }

   private:
    const SlicedBootstrapper* w_;
    Pose2 begin_;
    int slices_ = 0;
  };
  int slices_;
};

// A w search spread over steps: at most max_bootstraps_per_step searches go on per step, each
// takes its slices in as many steps, and its solution (the pose at Begin) is carried to the
// step it ends at by the odometry since.
TEST(Atlas, SlicedWIsBoundedPerStepAndCarriedToTheCurrentStep) {
  TestWorld w;
  auto sliced = std::make_shared<SlicedBootstrapper>(3);
  AtlasOptions o = TestWorld::Options();
  o.max_bootstraps_per_step = 1;
  ASSERT_LT(o.lifecycle.bootstrap_scans + 2, o.lifecycle.probation_scans);
  Atlas atlas(o, w.Factory(), sliced);
  int solved = 0;
  for (int i = 0; i < 120; ++i) {
    const double v = i < 60 ? 0.25 : -0.25;
    std::set<int64_t> unsolved;
    for (const Hypothesis& h : atlas.Hypotheses())
      if (h.state == HypothesisState::kJuvenile && !h.bootstrapped) unsolved.insert(h.id);
    sliced->continues = 0;
    atlas.Step(Pose2{v, 0.0, 0.0}, TestScan());
    CheckInvariants(atlas);
    EXPECT_LE(sliced->continues, 1);
    for (const Hypothesis& h : atlas.Hypotheses()) {
      if (!unsolved.count(h.id) || !h.bootstrapped) continue;
      ++solved;
      // Solved this step, after 3 steps of w: Z holds the 2 steps since Begin too.
      EXPECT_GE(h.steps, o.lifecycle.bootstrap_scans + 2);
      const Pose2 p = atlas.PoseOf(h).mean;
      EXPECT_NEAR(p.x, sliced->last_now.x + 0.5, 1e-9);
      EXPECT_NEAR(p.y, sliced->last_now.y, 1e-9);
      EXPECT_NEAR(p.theta, sliced->last_now.theta, 1e-9);
    }
  }
  EXPECT_GT(solved, 0);
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

// `image` (version 5) as an image of an older version: each frame's points are cut out and the
// version is set. Only the frame records are rewritten (their layout has not changed since 1).
std::string AsOlderImage(const std::string& image, uint32_t version) {
  const auto u64_at = [&image](size_t at) {
    uint64_t v = 0;
    std::memcpy(&v, image.data() + at, sizeof(v));
    return v;
  };
  constexpr size_t kHeader = 4 + 4 + 8 + 8 + 8 + 8;  // magic, version, step, ids, cursor
  uint32_t frames = 0;
  std::memcpy(&frames, image.data() + kHeader, sizeof(frames));
  std::string out = image.substr(0, kHeader + 4);
  std::memcpy(out.data() + 4, &version, sizeof(version));
  size_t at = kHeader + 4;
  for (uint32_t f = 0; f < frames; ++f) {
    const size_t map_at = at + 8 + 8 + 4;  // created, cooldown, retirements
    const size_t points_at = map_at + 8 + u64_at(map_at);
    out.append(image, at, points_at - at);
    at = points_at + 8 + u64_at(points_at);
  }
  out.append(image, at, std::string::npos);
  return out;
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

// Odometry that is not finite (or absurd), an increment covariance that is not finite, or a
// scan whose sensor mounting is not finite is refused for that step: nothing is updated, the
// dominant pose stays finite, later steps go on, and the image still round-trips. Without the
// check one NaN step left the dominant pose NaN for good and made frames without end.
TEST(Atlas, UnusableInputIsRefusedAndPoisonsNothing) {
  TestWorld w;
  Atlas a(TestWorld::Options(), w.Factory(), std::make_shared<FakeBootstrapper>());
  // The first step's odometry is not used: NaN there is harmless.
  EXPECT_EQ(a.Step(Pose2{NAN, 0.0, 0.0}, TestScan()).rejected_input, 0);
  for (int i = 0; i < 10; ++i) a.Step(Pose2{0.25, 0.0, 0.0}, TestScan());
  const Pose2 before = a.Dominant().pose.mean;
  const int frames = a.Graph().FrameCount();
  for (const Pose2& bad :
       {Pose2{NAN, 0.0, 0.0}, Pose2{0.0, 0.0, INFINITY}, Pose2{1e200, 0.0, 0.0}}) {
    EXPECT_EQ(a.Step(bad, TestScan()).rejected_input, 1);
    EXPECT_EQ(a.Dominant().pose.mean.x, before.x);
  }
  LaserScan bad_scan = TestScan();
  bad_scan.sensor_pose.theta = NAN;
  EXPECT_EQ(a.Step(Pose2{0.25, 0.0, 0.0}, bad_scan).rejected_input, 1);
  UncertainPose bad_increment;
  bad_increment.mean = Pose2{0.25, 0.0, 0.0};
  bad_increment.cov = Mat3::Identity() * NAN;
  EXPECT_EQ(a.Localize(bad_increment, TestScan()).rejected_input, 1);
  a.MaintainGraph();
  EXPECT_EQ(a.Graph().FrameCount(), frames);
  for (int i = 0; i < 10; ++i) {
    EXPECT_EQ(a.Step(Pose2{0.25, 0.0, 0.0}, TestScan()).rejected_input, 0);
    const UncertainPose p = a.Dominant().pose;
    EXPECT_TRUE(std::isfinite(p.mean.x) && std::isfinite(p.mean.y) && p.cov.allFinite());
  }
  Atlas b(TestWorld::Options(), w.Factory(), std::make_shared<FakeBootstrapper>());
  EXPECT_TRUE(b.Deserialize(a.Serialize()));
}

// Where the fields of a version 5 atlas image lie (atlas.cc, Serialize), for tests that
// corrupt one field of a real image.
struct ImageLayout {
  static constexpr size_t kStep = 8, kNextId = 16, kLastGenesis = 24;
  // A frame record: created step +0, seed cooldown +8, retirements +16.
  std::vector<size_t> frames;
  // An edge record: a +0, b +4, mean +8, cov +32, kind +104, origin +105, made step +106,
  // refined step +114, refinements +122.
  std::vector<size_t> edges;
  // A hypothesis record: id +0, frame +8, state +12, dominant +13, born step +14, steps +22,
  // q +26, failing +34, lagging +38, window capacity +42, head +46, size +50, ring +54.
  struct Hyp {
    size_t at = 0;
    size_t seed = std::string::npos;  // pose, then the upper covariance (juveniles)
    size_t nz = 0;                    // Z's scan count, then its scans
    std::vector<size_t> z;            // where each of Z's scans starts
    size_t end = 0;
  };
  std::vector<Hyp> hyps;
  size_t hyp_count = 0;  // the hypothesis count
};

template <typename T>
T Peek(const std::string& image, size_t at) {
  T v{};
  std::memcpy(&v, image.data() + at, sizeof(T));
  return v;
}

template <typename T>
std::string Poke(std::string image, size_t at, T v) {
  std::memcpy(image.data() + at, &v, sizeof(T));
  return image;
}

Mat3 PeekMat3(const std::string& image, size_t at) {
  Mat3 m;
  for (int i = 0; i < 9; ++i) m.data()[i] = Peek<double>(image, at + 8 * i);
  return m;
}

std::string PokeMat3(std::string image, size_t at, const Mat3& m) {
  for (int i = 0; i < 9; ++i) image = Poke(std::move(image), at + 8 * i, m.data()[i]);
  return image;
}

ImageLayout LayoutOf(const std::string& image) {
  ImageLayout l;
  size_t at = 40;
  const uint32_t frames = Peek<uint32_t>(image, at);
  at += 4;
  for (uint32_t f = 0; f < frames; ++f) {
    l.frames.push_back(at);
    at += 20;
    for (int blob = 0; blob < 2; ++blob) at += 8 + Peek<uint64_t>(image, at);
  }
  const uint32_t edges = Peek<uint32_t>(image, at);
  at += 4;
  for (uint32_t e = 0; e < edges; ++e, at += 126) l.edges.push_back(at);
  l.hyp_count = at;
  const uint32_t hyps = Peek<uint32_t>(image, at);
  at += 4;
  for (uint32_t i = 0; i < hyps; ++i) {
    ImageLayout::Hyp h;
    h.at = at;
    at += 54 + 8 * Peek<int32_t>(image, at + 42) + 13 + 1;
    const bool trial = image[at] != 0;
    ++at;
    if (trial) {
      at += 8 + Peek<uint64_t>(image, at);
      h.seed = at;
      at += 9 * 8;
    }
    h.nz = at;
    const uint32_t nz = Peek<uint32_t>(image, at);
    at += 4;
    for (uint32_t k = 0; k < nz; ++k) {
      h.z.push_back(at);
      at += 24 + 8 + 12 + 24;
      at += 8 + 4 * Peek<uint64_t>(image, at) + 13 + 8;
      at += 8 + 8 * Peek<uint64_t>(image, at);
    }
    h.end = at;
    l.hyps.push_back(h);
  }
  EXPECT_EQ(at, image.size()) << "the image layout changed: update ImageLayout";
  return l;
}

// Without the frames' maps the image is the whole image less each frame's map image; with the
// maps given apart it loads as the whole image does. A missing or undecodable map is named
// and leaves the atlas as it was; an older (version 5) image brings its own maps.
TEST(Atlas, FrameMapsKeptApartLoadBackWhole) {
  TestWorld w;
  Atlas a(TestWorld::Options(), w.Factory(), std::make_shared<FakeBootstrapper>());
  for (int i = 0; i < 75; ++i) a.Step(Pose2{i < 60 ? 0.25 : -0.25, 0.0, 0.0}, TestScan());
  ASSERT_GE(a.Graph().FrameCount(), 3);
  const std::string whole = a.Serialize();
  const std::string image = a.SerializeWithoutFrameMaps();
  std::vector<std::string> maps;
  size_t map_bytes = 0;
  for (FrameId f = 0; f < a.Graph().FrameCount(); ++f) {
    maps.push_back(a.Graph().Frame(f).map->Serialize());
    map_bytes += maps.back().size();
  }
  EXPECT_EQ(image.size() + map_bytes, whole.size());
  const auto given = [&maps](FrameId f) -> const std::string* {
    return f >= 0 && f < static_cast<FrameId>(maps.size()) ? &maps[f] : nullptr;
  };
  Atlas b(TestWorld::Options(), w.Factory(), std::make_shared<FakeBootstrapper>());
  ASSERT_TRUE(b.DeserializeWithFrameMaps(image, given).ok());
  EXPECT_TRUE(b.Serialize() == whole);
  EXPECT_TRUE(b.SerializeWithoutFrameMaps() == image);

  Atlas c(TestWorld::Options(), w.Factory(), std::make_shared<FakeBootstrapper>());
  c.Step(Pose2{}, TestScan());
  const std::string before = c.Serialize();
  EXPECT_FALSE(c.Deserialize(image));
  ImageLoadResult r = c.DeserializeWithFrameMaps(image, {});
  EXPECT_EQ(r.status, ImageLoadStatus::kFrameMapMissing);
  EXPECT_EQ(r.frame, 0);
  r = c.DeserializeWithFrameMaps(image, [&](FrameId f) { return f == 2 ? nullptr : given(f); });
  EXPECT_EQ(r.status, ImageLoadStatus::kFrameMapMissing);
  EXPECT_EQ(r.frame, 2);
  const std::string garbage = "not a map";
  r = c.DeserializeWithFrameMaps(image, [&](FrameId f) { return f == 1 ? &garbage : given(f); });
  EXPECT_EQ(r.status, ImageLoadStatus::kFrameMapMalformed);
  EXPECT_EQ(r.frame, 1);
  EXPECT_EQ(c.DeserializeWithFrameMaps(image.substr(0, image.size() - 1), given).status,
            ImageLoadStatus::kMalformed);
  EXPECT_TRUE(c.Serialize() == before);

  // Version 5: every map in the image (the maps given apart are not asked for); a frame whose
  // map image is empty there is malformed, not missing.
  const std::string v5 = Poke(whole, 4, uint32_t{5});
  Atlas d(TestWorld::Options(), w.Factory(), std::make_shared<FakeBootstrapper>());
  ASSERT_TRUE(d.DeserializeWithFrameMaps(v5, [](FrameId) -> const std::string* {
                 ADD_FAILURE() << "a version 5 image asked for a map";
                 return nullptr;
               }).ok());
  EXPECT_TRUE(d.Serialize() == whole);
  EXPECT_EQ(d.DeserializeWithFrameMaps(Poke(image, 4, uint32_t{5}), given).status,
            ImageLoadStatus::kMalformed);
}

// A frame's map_revision changes exactly when its map may have: at each step of a mature
// hypothesis in it, when a juvenile matures into it, when it is made. A frame whose revision
// did not change has the same map image; a step whose input is refused changes none.
TEST(Atlas, MapRevisionsFollowEveryChangeOfAFramesMap) {
  TestWorld w;
  Atlas a(TestWorld::Options(), w.Factory(), std::make_shared<FakeBootstrapper>());
  const auto mature_frames = [&a]() {
    std::set<FrameId> s;
    for (const Hypothesis& h : a.Hypotheses())
      if (h.state == HypothesisState::kMature) s.insert(h.frame);
    return s;
  };
  std::vector<uint64_t> revisions;
  std::vector<std::string> images;
  int matured = 0, retired = 0, unchanged = 0;
  for (int i = 0; i < 150; ++i) {
    std::set<FrameId> expected = mature_frames();
    const int frames_before = a.Graph().FrameCount();
    const StepStats& s = a.Step(Pose2{i < 60 || i >= 110 ? 0.25 : -0.25, 0.0, 0.0}, TestScan());
    matured += s.matured;
    retired += s.retired;
    const std::set<FrameId> after = mature_frames();
    expected.insert(after.begin(), after.end());
    for (FrameId f = frames_before; f < a.Graph().FrameCount(); ++f) expected.insert(f);
    for (FrameId f = 0; f < a.Graph().FrameCount(); ++f) {
      const MapFrame& frame = a.Graph().Frame(f);
      if (f >= static_cast<FrameId>(revisions.size())) {
        revisions.push_back(0);
        images.emplace_back();
      }
      const bool changed = frame.map_revision != revisions[f];
      EXPECT_EQ(changed, expected.count(f) == 1) << "step " << i << " frame " << f;
      if (!changed) {
        EXPECT_TRUE(frame.map->Serialize() == images[f]) << "step " << i << " frame " << f;
        ++unchanged;
      }
      revisions[f] = frame.map_revision;
      images[f] = frame.map->Serialize();
    }
  }
  EXPECT_GT(matured, 0);
  EXPECT_GT(retired, 0);
  EXPECT_GT(unchanged, 100);
  EXPECT_EQ(a.Step(Pose2{NAN, 0.0, 0.0}, TestScan()).rejected_input, 1);
  for (FrameId f = 0; f < a.Graph().FrameCount(); ++f)
    EXPECT_EQ(a.Graph().Frame(f).map_revision, revisions[f]);
  // A loaded atlas's frames are new to a saver.
  Atlas b(TestWorld::Options(), w.Factory(), std::make_shared<FakeBootstrapper>());
  ASSERT_TRUE(b.Deserialize(a.Serialize()));
  for (FrameId f = 0; f < b.Graph().FrameCount(); ++f)
    EXPECT_GT(b.Graph().Frame(f).map_revision, revisions[f]);
}

// Out and back along the corridor (as TraversalFallsBackToKnownFrames): refined edges, and
// with `undetermined_w` a juvenile accumulating Z (w stays undetermined) when the run stops.
std::string SavedRun(TestWorld* w, bool undetermined_w) {
  auto boot = undetermined_w
                  ? std::make_shared<FakeBootstrapper>(1 << 30, BootstrapOutcome::kUndetermined)
                  : std::make_shared<FakeBootstrapper>();
  Atlas a(TestWorld::Options(), w->Factory(), boot);
  const int bootstrap_scans = TestWorld::Options().lifecycle.bootstrap_scans;
  for (int i = 0; i < 120; ++i) {
    a.Step(Pose2{i < 60 ? 0.25 : -0.25, 0.0, 0.0}, TestScan());
    if (undetermined_w && i >= 60)
      for (const Hypothesis& h : a.Hypotheses())
        if (static_cast<int>(h.z.size()) > bootstrap_scans) return a.Serialize();
  }
  EXPECT_FALSE(undetermined_w) << "no juvenile accumulated Z: the test world changed";
  return a.Serialize();
}

// Whether an atlas like SavedRun's loads `image` (and round-trips it when it does).
bool Loads(TestWorld* w, const std::string& image) {
  Atlas b(TestWorld::Options(), w->Factory(), std::make_shared<FakeBootstrapper>());
  if (!b.Deserialize(image)) return false;
  EXPECT_TRUE(b.Serialize() == image);
  return true;
}

// A refined edge's refinement count is set as it was saved, in one step whatever its value: a
// count out of range (negative, more than one per step since the edge was made) is refused.
TEST(AtlasImage, RefinementCountIsCheckedAndRestoredWithoutALoop) {
  TestWorld w;
  const std::string image = SavedRun(&w, false);
  const ImageLayout l = LayoutOf(image);
  Atlas b(TestWorld::Options(), w.Factory(), std::make_shared<FakeBootstrapper>());
  ASSERT_TRUE(b.Deserialize(image));
  EXPECT_TRUE(b.Serialize() == image);
  int refined = -1;
  for (int e = 0; e < b.Graph().EdgeCount(); ++e)
    if (b.Graph().Edge(e).kind == EdgeKind::kRefined) refined = e;
  ASSERT_GE(refined, 0) << "no refined edge: the test world changed";
  const AtlasEdge& e = b.Graph().Edge(refined);
  EXPECT_GE(e.refinements, 1);
  EXPECT_GT(e.refined_step, e.made_step);
  const size_t at = l.edges[refined];
  EXPECT_EQ(Peek<int32_t>(image, at + 122), e.refinements);
  for (const int32_t n : {INT32_MAX, 1 << 30, 0, -1, INT32_MIN})
    EXPECT_FALSE(Loads(&w, Poke<int32_t>(image, at + 122, n))) << n;
  // A count of one refinement per step since the edge was made is the most there can be.
  const auto most = static_cast<int32_t>(e.refined_step - e.made_step);
  EXPECT_TRUE(Loads(&w, Poke<int32_t>(image, at + 122, most)));
  EXPECT_FALSE(Loads(&w, Poke<int32_t>(image, at + 122, most + 1)));
  // An edge that was never refined has no refinement to count.
  int plain = -1;
  for (int k = 0; k < b.Graph().EdgeCount(); ++k)
    if (b.Graph().Edge(k).kind != EdgeKind::kRefined) plain = k;
  if (plain >= 0) {
    EXPECT_FALSE(Loads(&w, Poke<int32_t>(image, l.edges[plain] + 122, 3)));
    EXPECT_FALSE(Loads(&w, Poke<int64_t>(image, l.edges[plain] + 114, 5)));
  }
  // A refined edge's kind without the refinements, or a made-by kind that is not a maker.
  EXPECT_FALSE(Loads(&w, Poke<uint8_t>(image, l.edges[0] + 105, 2)));
}

// Transforms, covariances and q are finite, covariances symmetric positive semi-definite.
TEST(AtlasImage, NonFiniteOrIndefiniteValuesAreRefused) {
  TestWorld w;
  const std::string image = SavedRun(&w, true);
  ASSERT_TRUE(Loads(&w, image));
  const ImageLayout l = LayoutOf(image);
  const double nan = std::numeric_limits<double>::quiet_NaN();
  const double inf = std::numeric_limits<double>::infinity();
  const size_t edge = l.edges[0];
  for (const double bad : {nan, inf, -inf}) {
    for (int k = 0; k < 3; ++k) EXPECT_FALSE(Loads(&w, Poke(image, edge + 8 + 8 * k, bad)));
    for (int k = 0; k < 9; ++k) EXPECT_FALSE(Loads(&w, Poke(image, edge + 32 + 8 * k, bad)));
  }
  const Mat3 cov = PeekMat3(image, edge + 32);
  Mat3 negative = cov;
  negative(1, 1) = -1.0;
  EXPECT_FALSE(Loads(&w, PokeMat3(image, edge + 32, negative)));
  Mat3 asymmetric = cov;
  asymmetric(0, 1) += 1e-3;
  EXPECT_FALSE(Loads(&w, PokeMat3(image, edge + 32, asymmetric)));
  Mat3 indefinite = cov;  // positive diagonal, a negative eigenvalue
  indefinite(0, 1) = indefinite(1, 0) = 2.0 * std::sqrt(cov(0, 0) * cov(1, 1)) + 1.0;
  EXPECT_FALSE(Loads(&w, PokeMat3(image, edge + 32, indefinite)));
  for (const ImageLayout::Hyp& h : l.hyps)
    for (const double bad : {nan, inf, -0.5, 1.5})
      EXPECT_FALSE(Loads(&w, Poke(image, h.at + 26, bad)));
  const ImageLayout::Hyp* juvenile = nullptr;
  for (const ImageLayout::Hyp& h : l.hyps)
    if (h.seed != std::string::npos) juvenile = &h;
  ASSERT_NE(juvenile, nullptr);
  EXPECT_FALSE(Loads(&w, Poke(image, juvenile->seed, nan)));
  EXPECT_FALSE(Loads(&w, Poke(image, juvenile->seed + 24, nan)));  // seed cov(0, 0)
  EXPECT_FALSE(Loads(&w, Poke(image, juvenile->seed + 24, -1.0)));
}

// A juvenile's Z holds fewer than probation_scans scans (atlas.cc, UpdateHypotheses): an image
// with more is refused before its scans are read (a 1000-scan Z made w take 609 MB).
TEST(AtlasImage, JuvenileZAboveProbationIsRefused) {
  TestWorld w;
  const std::string image = SavedRun(&w, true);
  ASSERT_TRUE(Loads(&w, image));
  const ImageLayout l = LayoutOf(image);
  const ImageLayout::Hyp* juvenile = nullptr;
  for (const ImageLayout::Hyp& h : l.hyps)
    if (!h.z.empty()) juvenile = &h;
  ASSERT_NE(juvenile, nullptr);
  const int probation = TestWorld::Options().lifecycle.probation_scans;
  // Z padded with copies of its last scan to `n` scans, the juvenile `n` steps old.
  const auto with_z = [&](uint32_t n) {
    std::string out = image.substr(0, juvenile->end);
    const std::string last = image.substr(juvenile->z.back(), juvenile->end - juvenile->z.back());
    for (size_t k = juvenile->z.size(); k < n; ++k) out += last;
    out = Poke<uint32_t>(out, juvenile->nz, n);
    out = Poke<int32_t>(out, juvenile->at + 22, static_cast<int32_t>(n));
    out = Poke<int64_t>(out, juvenile->at + 14, Peek<int64_t>(image, ImageLayout::kStep) - n);
    return out + image.substr(juvenile->end);
  };
  EXPECT_TRUE(Loads(&w, with_z(probation - 1)));
  EXPECT_FALSE(Loads(&w, with_z(probation)));
  EXPECT_FALSE(Loads(&w, with_z(1000)));
  // The count alone, past the end of the image.
  EXPECT_FALSE(Loads(&w, Poke<uint32_t>(image, juvenile->nz, UINT32_MAX)));
  // No more scans than steps since it was seeded.
  EXPECT_FALSE(Loads(
      &w, Poke<int32_t>(image, juvenile->at + 22, static_cast<int32_t>(juvenile->z.size()) - 1)));
}

// Step counters, ids and window counts are range-checked: none can overflow in later steps.
TEST(AtlasImage, CountersOutOfRangeAreRefused) {
  TestWorld w;
  const std::string image = SavedRun(&w, true);
  ASSERT_TRUE(Loads(&w, image));
  const ImageLayout l = LayoutOf(image);
  const int64_t step = Peek<int64_t>(image, ImageLayout::kStep);
  for (const int64_t bad : {INT64_MIN, int64_t{-1}, INT64_MAX})
    EXPECT_FALSE(Loads(&w, Poke(image, ImageLayout::kStep, bad))) << bad;
  for (const int64_t bad : {INT64_MIN, int64_t{-1}, INT64_MAX})
    EXPECT_FALSE(Loads(&w, Poke(image, ImageLayout::kNextId, bad))) << bad;
  for (const int64_t bad : {INT64_MIN, step + 1, INT64_MAX})
    EXPECT_FALSE(Loads(&w, Poke(image, ImageLayout::kLastGenesis, bad))) << bad;
  const size_t f = l.frames.back();
  for (const int64_t bad : {INT64_MIN, int64_t{-1}, step + 1})
    EXPECT_FALSE(Loads(&w, Poke(image, f, bad))) << bad;  // created
  for (const int64_t bad : {INT64_MIN, int64_t{-2}, INT64_MAX})
    EXPECT_FALSE(Loads(&w, Poke(image, f + 8, bad))) << bad;  // seed cooldown
  for (const int32_t bad : {INT32_MIN, -1, INT32_MAX})
    EXPECT_FALSE(Loads(&w, Poke(image, f + 16, bad))) << bad;  // retirements
  const size_t e = l.edges.back();
  for (const int64_t bad : {INT64_MIN, int64_t{-1}, step + 1})
    EXPECT_FALSE(Loads(&w, Poke(image, e + 106, bad))) << bad;  // made
  for (const int64_t bad : {INT64_MIN, int64_t{-2}, step + 1, INT64_MAX})
    EXPECT_FALSE(Loads(&w, Poke(image, e + 114, bad))) << bad;  // refined
  for (const ImageLayout::Hyp& h : l.hyps) {
    for (const int64_t bad : {INT64_MIN, int64_t{-1}, Peek<int64_t>(image, ImageLayout::kNextId)})
      EXPECT_FALSE(Loads(&w, Poke(image, h.at, bad))) << bad;  // id
    for (const int64_t bad : {INT64_MIN, int64_t{-1}, step + 1})
      EXPECT_FALSE(Loads(&w, Poke(image, h.at + 14, bad))) << bad;  // born
    for (const int32_t bad : {INT32_MIN, -1, INT32_MAX})
      EXPECT_FALSE(Loads(&w, Poke(image, h.at + 22, bad))) << bad;  // steps
    EXPECT_FALSE(Loads(&w, Poke(image, h.at + 34, Peek<int32_t>(image, h.at + 22) + 1)));
    for (const int32_t bad : {INT32_MIN, -1, INT32_MAX}) {
      EXPECT_FALSE(Loads(&w, Poke(image, h.at + 34, bad))) << bad;  // failing
      EXPECT_FALSE(Loads(&w, Poke(image, h.at + 38, bad))) << bad;  // lagging
    }
    // The quality window's counts: observations, matched of every entry.
    const int32_t cap = Peek<int32_t>(image, h.at + 42);
    for (int k = 0; k < cap; ++k) {
      const size_t entry = h.at + 54 + 8 * k;
      for (const int32_t bad : {INT32_MIN, -1, INT32_MAX})
        EXPECT_FALSE(Loads(&w, Poke(image, entry, bad))) << bad;
      EXPECT_FALSE(Loads(&w, Poke(image, entry + 4, Peek<int32_t>(image, entry) + 1)));
      EXPECT_FALSE(Loads(&w, Poke(image, entry + 4, -1)));
    }
    const size_t update = h.at + 54 + 8 * cap;  // the last update's counts
    for (int k = 0; k < 3; ++k)
      for (const int32_t bad : {INT32_MIN, -1, INT32_MAX})
        EXPECT_FALSE(Loads(&w, Poke(image, update + 4 * k, bad))) << bad;
  }
  // A step count within range and a counter left at its bound still load.
  EXPECT_TRUE(Loads(&w, Poke(image, ImageLayout::kLastGenesis, step)));
}

// After any step an atlas has a mature hypothesis (HandleFailures retires one only when another
// stays or Genesis makes one): an image without one is refused (it would output nothing). An
// atlas that never stepped (no frame) still round-trips.
TEST(AtlasImage, NoMatureHypothesisIsRefused) {
  TestWorld w;
  const std::string image = SavedRun(&w, true);
  ASSERT_TRUE(Loads(&w, image));
  const ImageLayout l = LayoutOf(image);
  // Only the juveniles kept.
  std::string juveniles = image.substr(0, l.hyp_count + 4);
  uint32_t kept = 0;
  for (const ImageLayout::Hyp& h : l.hyps) {
    if (static_cast<HypothesisState>(image[h.at + 12]) != HypothesisState::kJuvenile) continue;
    juveniles += image.substr(h.at, h.end - h.at);
    ++kept;
  }
  ASSERT_GE(kept, 1u);
  EXPECT_FALSE(Loads(&w, Poke(juveniles, l.hyp_count, kept)));
  // None at all.
  EXPECT_FALSE(Loads(&w, Poke(image.substr(0, l.hyp_count + 4), l.hyp_count, uint32_t{0})));
  Atlas fresh(TestWorld::Options(), w.Factory(), std::make_shared<FakeBootstrapper>());
  EXPECT_TRUE(Loads(&w, fresh.Serialize()));
}

// A scan of 181 returns 2 m from the sensor, over a half turn; the sensor 3 cm ahead of and
// 3 cm left of the robot (so that the endpoints lie inside cells, not on their borders).
LaserScan HalfTurnScan() {
  LaserScan s;
  s.sensor_pose = Pose2{0.03, 0.03, 0.0};
  s.angle_min = static_cast<float>(-std::numbers::pi / 2);
  s.angle_increment = static_cast<float>(std::numbers::pi / 180);
  s.max_range = 30.0f;
  s.ranges.assign(181, 2.0f);
  return s;
}

// Frames keep the endpoints of their mature hypotheses' scans (frame_points.h) when asked, the
// image carries them (version 5), and an older image loads with none.
TEST(Atlas, FramesKeepScanPointsThroughTheImage) {
  TestWorld w;
  AtlasOptions o = TestWorld::Options();
  Atlas off(o, w.Factory(), std::make_shared<FakeBootstrapper>());
  o.points.enabled = true;
  Atlas a(o, w.Factory(), std::make_shared<FakeBootstrapper>());
  for (int i = 0; i < 20; ++i) {
    a.Step(Pose2{0.25, 0.0, 0.0}, HalfTurnScan());
    off.Step(Pose2{0.25, 0.0, 0.0}, HalfTurnScan());
  }
  const FramePoints& points = a.Graph().Frame(0).points;
  EXPECT_GT(points.Size(), 50);
  EXPECT_LE(points.Size(), o.points.capacity);
  // The first scan, robot at the origin: 2 m ahead of the sensor, and 2 m left of it.
  EXPECT_TRUE(points.Contains(Vec2(2.03, 0.03)));
  EXPECT_TRUE(points.Contains(Vec2(0.03, 2.03)));
  EXPECT_FALSE(points.Contains(Vec2(-1.0, 0.0)));
  EXPECT_EQ(off.Graph().Frame(0).points.Size(), 0);

  const std::string image = a.Serialize();
  Atlas b(o, w.Factory(), std::make_shared<FakeBootstrapper>());
  ASSERT_TRUE(b.Deserialize(image));
  EXPECT_TRUE(b.Serialize() == image);
  EXPECT_EQ(b.Graph().Frame(0).points.Size(), points.Size());
  EXPECT_TRUE(b.Graph().Frame(0).points.Contains(Vec2(2.03, 0.03)));
  Atlas c(o, w.Factory(), std::make_shared<FakeBootstrapper>());
  ASSERT_TRUE(c.Deserialize(AsOlderImage(image, 4)));
  EXPECT_EQ(c.Graph().FrameCount(), a.Graph().FrameCount());
  EXPECT_EQ(c.Graph().Frame(0).points.Size(), 0);
  // A version 5 image whose frames lack their points is refused.
  EXPECT_FALSE(c.Deserialize(AsOlderImage(image, 5)));
}

TEST(Atlas, SonarStepsFeedASonarWAndRoundTripThroughTheImage) {
  TestWorld w;
  auto sonar_w = std::make_shared<FakeBootstrapper>(1 << 30, BootstrapOutcome::kUndetermined, true);
  Atlas a(TestWorld::Options(), w.Factory(), sonar_w);
  SonarReading reading;
  reading.returns = {SonarReturn{3, 1.25f}, SonarReturn{7, kNoReturn}};
  // Laser steps until a juvenile is seeded, then sonar steps: only these enter its Z.
  int i = 0;
  const auto juvenile = [&a]() {
    for (const Hypothesis& h : a.Hypotheses())
      if (h.state == HypothesisState::kJuvenile) return &h;
    return static_cast<const Hypothesis*>(nullptr);
  };
  for (; i < 60 && juvenile() == nullptr; ++i) a.Step(Pose2{0.25, 0.0, 0.0}, TestScan());
  ASSERT_NE(juvenile(), nullptr);
  const int steps_before = juvenile()->steps;
  EXPECT_TRUE(juvenile()->z.empty());
  a.Step(Pose2{0.25, 0.0, 0.0}, reading);
  a.Step(Pose2{0.25, 0.0, 0.0}, reading);
  ASSERT_NE(juvenile(), nullptr);
  ASSERT_EQ(juvenile()->steps, steps_before + 2);
  ASSERT_EQ(juvenile()->z.size(), 2u);
  EXPECT_EQ(juvenile()->z[1].sonar.returns.size(), 2u);
  EXPECT_EQ(juvenile()->z[1].odometry_delta.x, 0.25);
  const std::string image = a.Serialize();
  Atlas b(TestWorld::Options(), w.Factory(), sonar_w);
  ASSERT_TRUE(b.Deserialize(image));
  EXPECT_TRUE(b.Serialize() == image);
  const Hypothesis* restored = nullptr;
  for (const Hypothesis& h : b.Hypotheses())
    if (h.state == HypothesisState::kJuvenile) restored = &h;
  ASSERT_NE(restored, nullptr);
  ASSERT_EQ(restored->z.size(), 2u);
  EXPECT_EQ(restored->z[1].sonar.returns[0].transducer, 3);
  EXPECT_EQ(restored->z[1].sonar.returns[0].range, 1.25f);
  EXPECT_FALSE(IsReturn(restored->z[1].sonar.returns[1].range));
  // The juvenile's seed x_i* is in the image (version 4).
  const Hypothesis* saved = juvenile();
  EXPECT_EQ(restored->seed.mean.x, saved->seed.mean.x);
  EXPECT_TRUE(restored->seed.cov == saved->seed.cov);

  // A version 3 image (no seed after the trial map) still loads: the juvenile takes its current
  // pose as the seed and starts its Z again.
  const std::string trial = saved->trial_map->Serialize();
  const size_t at = image.find(trial);
  ASSERT_NE(at, std::string::npos);
  std::string v3 = image;
  v3.erase(at + trial.size(), 9 * sizeof(double));  // the seed: pose and upper covariance
  v3 = AsOlderImage(v3, 3);
  Atlas c(TestWorld::Options(), w.Factory(), sonar_w);
  ASSERT_TRUE(c.Deserialize(v3));
  const Hypothesis* old = nullptr;
  for (const Hypothesis& h : c.Hypotheses())
    if (h.state == HypothesisState::kJuvenile) old = &h;
  ASSERT_NE(old, nullptr);
  EXPECT_TRUE(old->z.empty());
  EXPECT_EQ(old->seed.mean.x, old->trial_map->RobotPose().mean.x);
  EXPECT_TRUE(old->seed.cov == old->trial_map->RobotPose().cov);
}

// A 16 m square room with a few unique walls. Each fake map reports the walls within 6 m of its
// own origin, in its own frame (the fake's dead reckoning is exact, so frame origins are known:
// `frame_in_world`, indexed by frame id, filled by PlaceNewFrames).
std::shared_ptr<std::vector<Pose2>> InstallSquareRoom(TestWorld* w) {
  w->radius = 2.0;
  auto frame_in_world = std::make_shared<std::vector<Pose2>>();
  const std::vector<std::pair<Vec2, Vec2>> walls{
      {{-3, -3}, {13, -3}}, {{13, -3}, {13, 13}}, {{13, 13}, {-3, 13}}, {{-3, 13}, {-3, -3}},
      {{3, 3}, {7, 3}},     {{7, 3}, {7, 7}},     {{1, 5}, {2, 9}},     {{-1, 0}, {0, 2}},
      {{10, 1}, {11, 0}},   {{9, 9}, {11, 10}},   {{0, 11}, {2, 12}},   {{5, -1}, {6, -2}}};
  w->script->lines = [walls, frame_in_world](int tag) {
    std::vector<MapLine> out;
    if (tag >= static_cast<int>(frame_in_world->size())) return out;
    const Pose2 f = (*frame_in_world)[tag];
    const Pose2 world_in_f = Inverse(f);
    for (const auto& [p, q] : walls) {
      const Vec2 o(f.x, f.y);
      if ((p - o).norm() > 6.0 && (q - o).norm() > 6.0) continue;
      const Vec2 a = world_in_f.TransformPoint(p), b = world_in_f.TransformPoint(q);
      MapLine l;
      const Vec2 d = (b - a).normalized();
      Vec2 n(-d.y(), d.x());
      l.rho = n.dot(a);
      if (l.rho < 0) {
        l.rho = -l.rho;
        n = -n;
      }
      l.alpha = std::atan2(n.y(), n.x());
      l.cov = Vec2(1e-4, 1e-5).asDiagonal();
      l.endpoint_a = a;
      l.endpoint_b = b;
      out.push_back(l);
    }
    return out;
  };
  return frame_in_world;
}

// Places frames made by the last step: a Genesis edge, just made, is exact; a frame without
// one (frame 0, or a resumed frame) starts at the robot's true pose.
void PlaceNewFrames(const AtlasGraph& g, const Pose2& truth, std::vector<Pose2>* frame_in_world) {
  for (FrameId f = static_cast<FrameId>(frame_in_world->size()); f < g.FrameCount(); ++f) {
    Pose2 pose = truth;
    for (const AtlasEdge& e : g.Edges())
      if (e.origin == EdgeKind::kGenesis && e.b == f)
        pose = Compose((*frame_in_world)[e.a], e.b_in_a.mean);
    frame_in_world->push_back(pose);
  }
}

// Every map-match edge agrees with the truth; returns how many join frames more than 5 apart.
int CheckMapMatchEdges(const AtlasGraph& g, const std::vector<Pose2>& frame_in_world) {
  int loop_edges = 0;
  for (const AtlasEdge& e : g.Edges()) {
    if (e.origin != EdgeKind::kMapMatch) continue;
    const Pose2 truth_b_in_a = Between(frame_in_world[e.a], frame_in_world[e.b]);
    EXPECT_NEAR(e.b_in_a.mean.x, truth_b_in_a.x, 0.05) << e.a << "-" << e.b;
    EXPECT_NEAR(e.b_in_a.mean.y, truth_b_in_a.y, 0.05) << e.a << "-" << e.b;
    EXPECT_NEAR(WrapAngle(e.b_in_a.mean.theta - truth_b_in_a.theta), 0.0, 0.01);
    loop_edges += std::abs(e.a - e.b) > 5;
  }
  return loop_edges;
}

Pose2 SquareRouteDelta(int i) {
  Pose2 delta{0.25, 0.0, 0.0};
  if (i > 0 && i % 40 == 0) delta.theta = std::numbers::pi / 2;
  return delta;
}

// Loop closure through the step: the robot drives a 10 m square and comes back to the start.
// Near the start, the current frame and frame 0 share their walls but are not adjacent:
// map-matching must add an edge, and every map-match edge must agree with the truth.
TEST(Atlas, MapMatchingClosesTheLoop) {
  TestWorld w;
  const auto frame_in_world = InstallSquareRoom(&w);
  AtlasOptions o = TestWorld::Options();
  ASSERT_FALSE(o.refine_map_match_edges);
  Atlas atlas(o, w.Factory(), std::make_shared<FakeBootstrapper>());
  Pose2 truth{};
  int accepted = 0, matched_reason = 0, self_matches = 0;
  for (int i = 0; i < 200; ++i) {
    const Pose2 delta = SquareRouteDelta(i);
    if (i > 0) truth = Compose(truth, delta);
    // Frames made by this step are placed before their lines are asked for (next step).
    const StepStats& s = atlas.Step(delta, TestScan());
    CheckInvariants(atlas);
    accepted += s.match_accepted;
    self_matches += s.self_matches;
    // Every map-matching outcome has exactly one reason; an accepted match has kMatched.
    int by_reason = 0;
    for (int n : s.match_reasons) by_reason += n;
    EXPECT_EQ(by_reason, s.match_accepted + s.match_rejected + s.match_ambiguous);
    EXPECT_GE(s.match_reasons[static_cast<int>(MapMatchReason::kMatched)], s.match_accepted);
    matched_reason += s.match_reasons[static_cast<int>(MapMatchReason::kMatched)];
    PlaceNewFrames(atlas.Graph(), truth, frame_in_world.get());
    // Map-match edges keep the maps' transform: they are not refined (AtlasOptions).
    for (const AtlasEdge& e : atlas.Graph().Edges()) {
      if (e.origin == EdgeKind::kMapMatch) {
        EXPECT_EQ(e.kind, EdgeKind::kMapMatch) << "step " << i;
      }
    }
  }
  EXPECT_GE(accepted, 1);
  EXPECT_GE(matched_reason, accepted);
  EXPECT_GE(self_matches, 2) << "self-matches are computed in steps of their own";
  const int loop_edges = CheckMapMatchEdges(atlas.Graph(), *frame_in_world);
  EXPECT_GE(loop_edges, 1) << "no edge closes the loop";
  std::printf("frames %d, map-match edges accepted %d, loop edges %d\n", atlas.Graph().FrameCount(),
              accepted, loop_edges);
}

// A matcher whose searches take `slices` steps and accept the prior's placement.
class SlicedMatcher : public MapMatcher {
 public:
  explicit SlicedMatcher(int slices) : slices_(slices) {}
  MapMatch Match(const LocalMap&, const LocalMap&, const UncertainPose*) const override {
    ADD_FAILURE() << "the atlas matches through Begin";
    return {};
  }
  std::unique_ptr<MapMatchSearch> Begin(const LocalMap&, const LocalMap&,
                                        const UncertainPose* prior) const override {
    ++begun;
    return std::make_unique<Search>(this, prior ? *prior : UncertainPose{});
  }
  mutable int begun = 0, continues = 0;  // continues: reset by the test every step

 private:
  class Search : public MapMatchSearch {
   public:
    Search(const SlicedMatcher* m, const UncertainPose& prior) : m_(m) {
      result_.result = MapMatchResult::kAccepted;
      result_.reason = MapMatchReason::kMatched;
      result_.b_in_a = prior;
    }
    bool Continue(const LocalMap&, const LocalMap&) override {
      ++m_->continues;
      return ++slices_ >= m_->slices_;
    }
    const MapMatch& Result() const override { return result_; }

   private:
    const SlicedMatcher* m_;
    int slices_ = 0;
    MapMatch result_;
  };
  int slices_;
};

// With a matcher, one search goes on at a time, one slice per step, and an accepted one adds
// its edge at the step it ends; while it is pending, w and map-matching take turns.
TEST(Atlas, SlicedMapMatchingGoesOnOneSlicePerStep) {
  TestWorld w;
  const auto frame_in_world = InstallSquareRoom(&w);
  AtlasOptions o = TestWorld::Options();
  o.max_bootstraps_per_step = 1;
  auto matcher = std::make_shared<SlicedMatcher>(4);
  auto sliced_w = std::make_shared<SlicedBootstrapper>(2);
  Atlas atlas(o, w.Factory(), sliced_w);
  atlas.SetMapMatcher(matcher);
  Pose2 truth{};
  int accepted = 0, both = 0, w_steps = 0, match_steps = 0;
  for (int i = 0; i < 200; ++i) {
    const Pose2 delta = SquareRouteDelta(i);
    if (i > 0) truth = Compose(truth, delta);
    matcher->continues = 0;
    sliced_w->continues = 0;
    const int begun = matcher->begun;
    const StepStats& s = atlas.Step(delta, TestScan());
    CheckInvariants(atlas);
    EXPECT_LE(matcher->continues, 1);
    EXPECT_LE(matcher->begun - begun, 1);
    // Only a search's first slice (the step it begins) may share a step with w.
    both += matcher->continues > 0 && sliced_w->continues > 0 && matcher->begun == begun;
    w_steps += sliced_w->continues > 0;
    match_steps += matcher->continues > 0;
    accepted += s.match_accepted;
    EXPECT_LE(s.match_accepted + s.match_rejected + s.match_ambiguous, matcher->continues);
    PlaceNewFrames(atlas.Graph(), truth, frame_in_world.get());
  }
  EXPECT_EQ(both, 0);
  EXPECT_GT(w_steps, 0);
  EXPECT_GT(match_steps, 3 * accepted);  // each accepted search took 4 steps
  EXPECT_GE(accepted, 1);
}

// The two halves of a step: Localize() gives the step's output, MaintainGraph() (map-matching,
// refinement) never changes it, and the halves together are exactly Step().
TEST(Atlas, LocalizeThenMaintainGraphIsStepAndKeepsTheDominantPose) {
  TestWorld w1, w2;
  const auto world1 = InstallSquareRoom(&w1);
  const auto world2 = InstallSquareRoom(&w2);
  Atlas whole(TestWorld::Options(), w1.Factory(), std::make_shared<FakeBootstrapper>());
  Atlas halves(TestWorld::Options(), w2.Factory(), std::make_shared<FakeBootstrapper>());
  Pose2 truth{};
  int graph_changes = 0;
  for (int i = 0; i < 200; ++i) {
    const Pose2 delta = SquareRouteDelta(i);
    if (i > 0) truth = Compose(truth, delta);
    whole.Step(delta, TestScan());
    halves.Localize(delta, TestScan());
    const DominantOutput before = halves.Dominant();
    const int edges_before = halves.Graph().EdgeCount();
    const StepStats& s = halves.MaintainGraph();
    const DominantOutput after = halves.Dominant();
    ASSERT_TRUE(after.valid);
    EXPECT_EQ(before.hypothesis, after.hypothesis);
    EXPECT_EQ(before.frame, after.frame);
    EXPECT_EQ((before.pose.mean.ToVector() - after.pose.mean.ToVector()).norm(), 0.0);
    EXPECT_EQ(before.q, after.q);
    graph_changes += (halves.Graph().EdgeCount() != edges_before) + s.refined;
    EXPECT_EQ(s.step, whole.LastStats().step);
    EXPECT_EQ(s.match_accepted, whole.LastStats().match_accepted);
    EXPECT_EQ(s.refined, whole.LastStats().refined);
    PlaceNewFrames(whole.Graph(), truth, world1.get());
    PlaceNewFrames(halves.Graph(), truth, world2.get());
  }
  EXPECT_GT(graph_changes, 0) << "MaintainGraph never did anything: the test shows nothing";
  EXPECT_TRUE(whole.Serialize() == halves.Serialize());
}

// A restart: the atlas of a whole lap is kept, the robot resumes in a new, unconnected frame
// somewhere on the square, and map-matching without a prior must join the new part to the old
// one, with a transform that agrees with the truth.
TEST(Atlas, ResumedFrameIsReconnectedByMapMatching) {
  TestWorld w;
  const auto frame_in_world = InstallSquareRoom(&w);
  Atlas atlas(TestWorld::Options(), w.Factory(), std::make_shared<FakeBootstrapper>());
  Pose2 truth{};
  int i = 0;
  for (; i < 170; ++i) {
    const Pose2 delta = SquareRouteDelta(i);
    if (i > 0) truth = Compose(truth, delta);
    atlas.Step(delta, TestScan());
    PlaceNewFrames(atlas.Graph(), truth, frame_in_world.get());
  }
  const int old_frames = atlas.Graph().FrameCount();
  const int old_edges = atlas.Graph().EdgeCount();
  const FrameId resumed = atlas.ResumeInNewFrame();
  PlaceNewFrames(atlas.Graph(), truth, frame_in_world.get());
  EXPECT_EQ(resumed, old_frames);
  EXPECT_EQ(atlas.Graph().EdgeCount(), old_edges);
  ASSERT_EQ(atlas.Hypotheses().size(), 1u);
  EXPECT_EQ(atlas.Dominant().frame, resumed);
  EXPECT_EQ(atlas.Dominant().pose.mean.x, 0.0);
  EXPECT_EQ(atlas.Dominant().pose.cov, Mat3::Zero());
  int unconnected = 0, joining = 0;
  for (; i < 240; ++i) {
    const Pose2 delta = SquareRouteDelta(i % 160);
    truth = Compose(truth, delta);
    const StepStats& s = atlas.Step(delta, TestScan());
    CheckInvariants(atlas);
    EXPECT_LE(s.match_unconnected, atlas.Options().resume_candidates_per_step);
    unconnected += s.match_unconnected;
    PlaceNewFrames(atlas.Graph(), truth, frame_in_world.get());
  }
  for (const AtlasEdge& e : atlas.Graph().Edges())
    joining += e.origin == EdgeKind::kMapMatch && (e.a < old_frames) != (e.b < old_frames);
  EXPECT_GT(unconnected, 0);
  EXPECT_GE(joining, 1) << "the resumed part was never joined to the saved atlas";
  CheckMapMatchEdges(atlas.Graph(), *frame_in_world);
}

// Serialize, Deserialize into a fresh atlas, resume: the saved frames and edges are kept and
// the robot is alone in a new frame.
TEST(Atlas, ResumeAfterDeserializeKeepsTheSavedAtlas) {
  TestWorld w;
  Atlas a(TestWorld::Options(), w.Factory(), std::make_shared<FakeBootstrapper>());
  for (int i = 0; i < 75; ++i) a.Step(Pose2{0.25, 0.0, 0.0}, TestScan());
  Atlas b(TestWorld::Options(), w.Factory(), std::make_shared<FakeBootstrapper>());
  ASSERT_TRUE(b.Deserialize(a.Serialize()));
  const FrameId f = b.ResumeInNewFrame();
  EXPECT_EQ(b.Graph().FrameCount(), a.Graph().FrameCount() + 1);
  EXPECT_EQ(b.Graph().EdgeCount(), a.Graph().EdgeCount());
  EXPECT_TRUE(b.Graph().Frame(f).edges.empty());
  ASSERT_EQ(b.Hypotheses().size(), 1u);
  EXPECT_EQ(b.Hypotheses()[0].frame, f);
  for (int i = 0; i < 20; ++i) {
    b.Step(Pose2{0.25, 0.0, 0.0}, TestScan());
    CheckInvariants(b);
  }
}

// Sonar steps: a map without a sonar path gets no evidence from them, so q does not move, and
// the robot still moves with the odometry.
// A hypothesis that has not seen an observation yet (its window's ring is allocated at the
// first one: here the first step is a sonar reading without echoes; also a hypothesis just made
// by Genesis) is saved and read back: every image the atlas writes can be read.
TEST(Atlas, ImageWithAHypothesisThatSawNothingYetRoundTrips) {
  TestWorld w;
  Atlas a(TestWorld::Options(), w.Factory(), nullptr);
  SonarReading r;
  r.returns.resize(16);
  a.Step(Pose2{}, r);
  ASSERT_EQ(a.Hypotheses().size(), 1u);
  ASSERT_EQ(a.Hypotheses()[0].window.Size(), 0);
  Atlas b(TestWorld::Options(), w.Factory(), nullptr);
  ASSERT_TRUE(b.Deserialize(a.Serialize()));
  EXPECT_TRUE(b.Serialize() == a.Serialize());
  b.Step(Pose2{0.1, 0.0, 0.0}, TestScan());
  EXPECT_EQ(b.Hypotheses()[0].window.Size(), 1);
}

TEST(Atlas, SonarStepOnAMapWithoutSonarOnlyPredicts) {
  TestWorld w;
  Atlas a(TestWorld::Options(), w.Factory(), nullptr);
  a.Step(Pose2{}, TestScan());
  for (int i = 0; i < 5; ++i) a.Step(Pose2{0.1, 0.0, 0.0}, TestScan());
  const double q = a.Dominant().q;
  SonarReading r;
  r.returns.resize(16);
  for (int i = 0; i < 10; ++i) {
    const StepStats& s = a.Step(Pose2{0.1, 0.0, 0.0}, r);
    CheckInvariants(a);
    EXPECT_EQ(s.step, 7 + i);
  }
  EXPECT_NEAR(a.Dominant().pose.mean.x, 1.5, 1e-9);
  EXPECT_NEAR(a.Dominant().q, q, 0.05);
}

}  // namespace
}  // namespace atlas
