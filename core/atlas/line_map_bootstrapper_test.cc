#include "core/atlas/line_map_bootstrapper.h"

#include <gtest/gtest.h>

#include <cstdio>
#include <cstdlib>
#include <utility>
#include <vector>

#include "core/atlas/atlas.h"
#include "core/localmap/line_ekf_map.h"
#include "core/testing/fake_wall_scanner.h"
#include "sim/corridor.h"

namespace atlas {
namespace {

struct Corridor {
  LocalMapOptions options;
  FakeWallScanner scanner;
  Pose2 start{2.0, 0.0, 0.0};  // the map-frame origin, in the world
  LineEkfMap map{options};
  Pose2 truth = start;  // robot in the world

  explicit Corridor(std::vector<sim::Wall> walls = sim::CorridorWalls(30.0, 2.4))
      : scanner(std::move(walls), FakeLaserOptions{}, 11) {
    map.Update(scanner.Scan(truth), true);
    for (int i = 0; i < 6; ++i) Move(Pose2{0.2, 0.0, 0.0}, &map, true);
  }
  ScanUpdate Move(const Pose2& delta, LocalMap* m, bool grow) {
    truth = Compose(truth, delta);
    m->Predict(delta);
    return m->Update(scanner.Scan(truth), grow);
  }
  Pose2 TruthInMap() const { return Between(start, truth); }

  // A juvenile seeded with `offset` from the true pose, after `n` scans.
  PoseBootstrap Juvenile(const Pose2& offset, int n, bool blind = false) {
    std::unique_ptr<LocalMap> trial = map.Clone();
    trial->ResetRobotPose(
        UncertainPose{Compose(TruthInMap(), offset), Vec3(0.09, 0.09, 0.01).asDiagonal()});
    std::vector<JuvenileScan> z;
    for (int i = 0; i < n; ++i) {
      const Pose2 delta{0.15, 0.0, 0.01};
      truth = Compose(truth, delta);
      trial->Predict(delta);
      LaserScan scan = scanner.Scan(truth);
      if (blind) scan.ranges.assign(scan.ranges.size(), kNoReturn);
      const ScanUpdate u = trial->Update(scan, false);
      z.push_back(JuvenileScan{delta, ScanObservation(scan), u, SonarReading{}});
    }
    return LineMapBootstrapper(options).Solve(*trial, map, z, trial->RobotPose());
  }
};

TEST(LineMapBootstrapper, SolvesThePoseFromTheScansNotTheSeed) {
  Corridor a, b;
  const PoseBootstrap ra = a.Juvenile(Pose2{0.1, -0.05, 0.02}, 4);
  const PoseBootstrap rb = b.Juvenile(Pose2{-0.1, 0.05, -0.02}, 4);
  ASSERT_EQ(ra.outcome, BootstrapOutcome::kSolved);
  ASSERT_EQ(rb.outcome, BootstrapOutcome::kSolved);
  const Pose2 t = a.TruthInMap();
  EXPECT_NEAR(ra.pose.mean.x, t.x, 0.05);
  EXPECT_NEAR(ra.pose.mean.y, t.y, 0.05);
  EXPECT_NEAR(ra.pose.mean.theta, t.theta, 0.01);
  // Opposite seeds, same answer (up to the juveniles' own map updates).
  EXPECT_NEAR(ra.pose.mean.x, rb.pose.mean.x, 0.03);
  EXPECT_NEAR(ra.pose.mean.y, rb.pose.mean.y, 0.03);
  EXPECT_GT(ra.pose.cov.determinant(), 0.0);
}

// Two parallel walls and nothing else: the scans fix the heading and the distance to the walls
// but not the position along them. w cannot tell yet (kUndetermined: the atlas keeps the
// juvenile and tries again with more scans), which is not a contradiction (kFailed).
TEST(LineMapBootstrapper, UndeterminedWhenOnlyParallelWallsMatch) {
  Corridor c({sim::Wall{Vec2(-100.0, 1.2), Vec2(100.0, 1.2)},
              sim::Wall{Vec2(-100.0, -1.2), Vec2(100.0, -1.2)}});
  ASSERT_EQ(c.map.Complexity(), 2);
  EXPECT_EQ(c.Juvenile(Pose2{0.05, 0.0, 0.0}, 4).outcome, BootstrapOutcome::kUndetermined);
}

TEST(LineMapBootstrapper, FailsWithoutExplainedMeasurements) {
  Corridor c;
  EXPECT_EQ(c.Juvenile(Pose2{}, 4, /*blind=*/true).outcome, BootstrapOutcome::kFailed);
  EXPECT_EQ(LineMapBootstrapper(c.options).Solve(c.map, c.map, {}, UncertainPose{}).outcome,
            BootstrapOutcome::kFailed);
}

}  // namespace
}  // namespace atlas

namespace atlas {
namespace {

// The atlas driving real line EKF maps (the localmap helper's) along a corridor and back: the
// corridor walls explain every scan, so no frame is needed beyond the first, and the output
// stays on the true trajectory (frame 0's origin is the true start pose).
TEST(AtlasWithLineMaps, CorridorOutAndBack) {
  LocalMapOptions lo;
  lo.capacity = 6;
  FakeWallScanner scanner(sim::CorridorWalls(30.0, 2.4), FakeLaserOptions{}, 5);
  AtlasOptions o;
  Atlas atlas(
      o, [lo] { return std::make_unique<LineEkfMap>(lo); },
      std::make_shared<LineMapBootstrapper>(lo));
  Pose2 truth{0.0, 0.0, 0.0};
  int max_frame = 0;
  const int n = 2 * 110;
  for (int i = 0; i < n; ++i) {
    Pose2 delta{0.2, 0.0, 0.0};
    if (i == 110) delta = Pose2{0.0, 0.0, 3.14159265358979};  // turn on the spot
    truth = Compose(truth, delta);
    const StepStats& s = atlas.Step(delta, scanner.Scan(truth));
    max_frame = std::max(max_frame, static_cast<int>(s.dominant_frame));
    if (getenv("ATLAS_TRACE") && i % 5 == 0) {
      std::printf("%3d dom %d frames %d |", i, s.dominant_frame, s.frames);
      for (const Hypothesis& h : atlas.Hypotheses())
        std::printf(" [%d %s q%.2f obs %d/%d c%d det %.2g]", h.frame, HypothesisStateName(h.state),
                    h.q, h.window.Matched(), h.window.Observations(),
                    atlas.Graph().Frame(h.frame).map->Complexity(),
                    atlas.PoseOf(h).cov.determinant());
      std::printf("\n");
    }
    ASSERT_LE(s.hypotheses_alive, o.max_hypotheses);
  }
  const DominantOutput d = atlas.Dominant();
  ASSERT_TRUE(d.valid);
  EXPECT_EQ(d.frame, 0);
  EXPECT_EQ(atlas.Graph().FrameCount(), 1);
  EXPECT_EQ(max_frame, 0);
  EXPECT_NEAR(d.pose.mean.x, truth.x, 0.3);
  EXPECT_NEAR(d.pose.mean.y, truth.y, 0.1);
  EXPECT_NEAR(std::abs(WrapAngle(d.pose.mean.theta - truth.theta)), 0.0, 0.02);
}

}  // namespace
}  // namespace atlas
