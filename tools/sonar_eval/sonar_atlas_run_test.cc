// atlas-sonar-eval's atlases are atlasd's; and Condition 2 in a simulated sonar-only atlas run
// (paper, Sections II-A and IV): round a corridor loop with an alcove every 4 m, the atlas must
// refuse the ambiguous map-matches and add no false loop closure.

#include "tools/sonar_eval/sonar_atlas_run.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <memory>
#include <numbers>

#include "atlas_paths.h"
#include "core/sonar/sonar_local_map.h"
#include "core/sonar/sonar_map_bootstrapper.h"
#include "formats/config/config_loader.h"
#include "formats/config/mapper_config.h"
#include "sim/route.h"
#include "sim/simulation.h"
#include "sim/sonar_model.h"
#include "tools/sonar_eval/alcove_loop_world.h"
#include "tools/sonar_eval/corridor_run.h"

namespace atlas::sonar_eval {
namespace {

// atlas-sonar-eval atlas maps as atlasd does with config/atlasd.toml: its sonar atlas is the one
// of the sonar ring alone, its laser atlas the one of line maps of the laser alone, field by
// field; its maps have the shipped capacity and differ from atlasd's only in the noise models.
TEST(SonarEvalDefaults, TheAtlasesAreThoseOfTheShippedFile) {
  const ConfigResult r =
      LoadConfigFile(ATLAS_SOURCE_DIR "/config/atlasd.toml", ValidateMapperOptions);
  for (const ConfigError& e : r.errors) ADD_FAILURE() << e.ToString();
  ASSERT_TRUE(r.ok());
  MapperSettings laser = ToMapperSettings(r.options);
  ASSERT_EQ(laser.sensors, RangeSensors::kLaser);
  laser.grid_frames = false;  // the paper's Section IV compares line maps
  EXPECT_TRUE(LaserEvalAtlasOptions() == AtlasOptionsOf(laser));

  MapperSettings sonar = laser;
  sonar.sensors = RangeSensors::kSonar;
  for (const int transducers : {24, 16}) {
    const sim::SonarOptions ring = SonarOptionsFor(transducers);
    sonar.sonar_ring = ring.ring;
    for (const bool w : {true, false}) {
      sonar.sonar_bootstrap = w;
      ASSERT_EQ(ValidateMapperSettings(sonar), "");
      EXPECT_TRUE(SonarEvalAtlasOptions(ring.ring, w) == AtlasOptionsOf(sonar)) << transducers;
    }
    // --probation replaces the probation, whatever w asks for.
    EXPECT_EQ(SonarEvalAtlasOptions(ring.ring, true, 3).lifecycle.probation_scans, 3);

    EXPECT_EQ(EvalMapCapacity(), LocalMapOptionsOf(sonar).capacity);
    const SonarLocalMapOptions maps = SimulatedMapOptions(RangeSensors::kSonar, EvalMapCapacity(),
                                                          WheelOdometryNoiseOptions{}, ring);
    ASSERT_EQ(maps.Validate(), "");
    EXPECT_EQ(maps.ring.size(), ring.ring.size());
    LocalMapOptions atlasd = LocalMapOptionsOf(sonar);
    atlasd.extraction = maps.line_map.extraction;
    atlasd.odometry = maps.line_map.odometry;
    EXPECT_TRUE(maps.line_map == atlasd);
  }
}

TEST(AlcoveLoopWorld, AlcovesRepeatAtThePeriodAndTheRouteGoesRound) {
  AlcoveLoopOptions o;
  ASSERT_EQ(o.Validate(), "");
  const sim::World w = AlcoveLoopWorld(o);
  // Alcove back walls: alcove_width long, alcove_depth outside the outer rectangle.
  std::vector<double> bottom;  // x of the back walls on the side y = 0
  for (const sim::Wall& wall : w.walls) {
    if (std::abs(wall.a.y() + o.alcove_depth) < 1e-9 && std::abs(wall.b.y() - wall.a.y()) < 1e-9) {
      EXPECT_NEAR(std::abs(wall.b.x() - wall.a.x()), o.alcove_width, 1e-9);
      bottom.push_back(std::min(wall.a.x(), wall.b.x()));
    }
  }
  ASSERT_GE(bottom.size(), 5u);
  for (size_t k = 1; k < bottom.size(); ++k) EXPECT_NEAR(bottom[k] - bottom[k - 1], o.period, 1e-9);
  // The route graph is one ring on the centreline: every node has degree 2.
  std::vector<int> degree(w.nodes.size(), 0);
  for (const sim::RouteEdge& e : w.edges) ++degree[e.from], ++degree[e.to];
  for (int d : degree) EXPECT_EQ(d, 2);
  // A route of two laps visits every node twice: round the loop, one way.
  const double lap = 2.0 * (o.length - o.corridor_width) + 2.0 * (o.width - o.corridor_width);
  const std::vector<int> route = sim::PlanRoute(w, 2.0 * lap, sim::StartNode(w), 7);
  std::vector<int> visits(w.nodes.size(), 0);
  for (size_t k = 1; k < route.size(); ++k) ++visits[route[k]];
  for (int v : visits) EXPECT_GE(v, 2);
}

TEST(AlcoveLoopWorld, ValidateNamesTheBadOption) {
  AlcoveLoopOptions o;
  o.period = 1.0;  // not wider than an alcove
  EXPECT_NE(o.Validate().find("period"), std::string::npos);
  o = AlcoveLoopOptions{};
  o.width = 4.0;
  EXPECT_NE(o.Validate().find("width"), std::string::npos);
}

TEST(WallLines, LinesInTheFrameAndTheirDistanceToAMappedLine) {
  // A wall along y = 2 (normal +y) and one along x = -1, seen from a frame whose true origin
  // is at (1, 0) turned by 90 degrees: in that frame the first lies at x = 2 (rho 2, alpha 0),
  // the second at y = 2 (rho 2, alpha 90 deg).
  const std::vector<sim::Wall> walls = {{Vec2(-5, 2), Vec2(5, 2)}, {Vec2(-1, -5), Vec2(-1, 5)}};
  EXPECT_NEAR(WallLine(walls[0]).x(), 2.0, 1e-12);
  EXPECT_NEAR(std::abs(WrapAngle(WallLine(walls[0]).y())), std::numbers::pi / 2, 1e-12);
  const std::vector<Vec2> in_frame = WallLinesInFrame(walls, Pose2{1.0, 0.0, std::numbers::pi / 2});
  ASSERT_EQ(in_frame.size(), 2u);
  EXPECT_NEAR(in_frame[0].x(), 2.0, 1e-12);
  EXPECT_NEAR(in_frame[0].y(), 0.0, 1e-12);
  EXPECT_NEAR(in_frame[1].x(), 2.0, 1e-12);
  EXPECT_NEAR(in_frame[1].y(), std::numbers::pi / 2, 1e-12);

  MapLine l;
  l.rho = 2.1;
  l.alpha = 0.02;
  l.cov = Vec2(0.05 * 0.05, 0.01 * 0.01).asDiagonal();
  EXPECT_NEAR(NeesAgainstNearestWall(l, in_frame), 4.0 + 4.0,
              1e-9);  // (0.1/0.05)^2 + (0.02/0.01)^2
  // The same line written with the opposite normal is the same distance away.
  l.rho = -2.1;
  l.alpha = 0.02 + std::numbers::pi;
  EXPECT_NEAR(NeesAgainstNearestWall(l, in_frame), 8.0, 1e-9);
  EXPECT_FALSE(FarFromEveryWall(Vec2(2.2, 0.1), in_frame));
  EXPECT_TRUE(FarFromEveryWall(Vec2(2.3, 0.0), in_frame));   // 0.3 m off
  EXPECT_TRUE(FarFromEveryWall(Vec2(2.0, 0.25), in_frame));  // 14 degrees off
  EXPECT_FALSE(FarFromEveryWall(Vec2(-2.0, -std::numbers::pi / 2), in_frame));
}

TEST(PoseNees, FloorKeepsASingularCovarianceFinite) {
  UncertainPose p;  // zero covariance, as right after Genesis
  EXPECT_NEAR(PoseNees(p, Pose2{1e-3, 0.0, 0.0}), 1.0, 1e-9);
  p.cov = Vec3(0.01, 0.04, 0.0001).asDiagonal();
  EXPECT_NEAR(PoseNees(p, Pose2{0.1, 0.0, 0.0}), 0.01 / (0.01 + 1e-6), 1e-9);
}

// The seeded run: 0.3 km (3.2 laps) with a 24-transducer ring, sonar only, with atlas-sonar-eval's
// atlas (atlasd's, with w): at least 4 frames, a true closure, and matches refused as ambiguous.
TEST(SonarAtlasCondition2, AmbiguousMatchesAreRefusedAndNoFalseClosureIsAdded) {
  const AlcoveLoopOptions loop;
  const sim::World world = AlcoveLoopWorld(loop);
  sim::SimulationOptions so;
  so.length_m = 300.0;
  so.laser = false;
  so.sonar = true;
  so.sonar_options.ring = sim::B21SonarRing();
  so.seed = 61;
  ASSERT_EQ(so.Validate(), "");
  SimRecording run;
  const sim::SimulationSummary sum = sim::Simulate(world, so, run);
  ASSERT_EQ(sum.error, "");
  const SonarLocalMapOptions mo = SimulatedMapOptions(RangeSensors::kSonar, EvalMapCapacity(),
                                                      so.odometry_options, so.sonar_options);
  ASSERT_EQ(mo.Validate(), "");
  const AtlasOptions ao = SonarEvalAtlasOptions(so.sonar_options.ring, true);
  Atlas atlas(
      ao, [mo]() { return std::make_unique<SonarLocalMap>(mo); },
      std::make_shared<SonarMapBootstrapper>());
  const AtlasRunReport r = RunAtlas(atlas, run, true);

  ASSERT_GT(r.steps, 1000);
  EXPECT_GE(r.frames, 4);
  // Refused as ambiguous, and for Condition 2's reasons: repetitive structure, a rival, or a
  // direction of t that rests on one line pair.
  EXPECT_GE(r.ambiguous, 1);
  EXPECT_EQ(r.ambiguous, r.reasons[static_cast<int>(MapMatchReason::kRepetitive)] +
                             r.reasons[static_cast<int>(MapMatchReason::kRivalTransform)] +
                             r.reasons[static_cast<int>(MapMatchReason::kSinglePair)]);
  // The loop is closed, and every edge added by map-matching agrees with the ground truth: no
  // false closure.
  EXPECT_GE(r.accepted, 1);
  EXPECT_EQ(r.closures.map_match_edges, r.accepted);
  EXPECT_EQ(r.closures.unreferenced, 0);
  EXPECT_EQ(r.closures.false_chi2, 0);
  EXPECT_EQ(r.closures.gross, 0);
  ASSERT_EQ(static_cast<int>(r.as_made.size()), r.closures.map_match_edges);
  for (const replay::ClosureVerdict& v : r.as_made) EXPECT_FALSE(v.false_chi2) << v.a << "-" << v.b;
  for (const replay::ClosureVerdict& v : r.closures.edges) {
    EXPECT_LT(std::hypot(v.error[0], v.error[1]), 0.5) << v.a << "-" << v.b;
    EXPECT_LT(v.d2, 14.16) << v.a << "-" << v.b;
  }
}

}  // namespace
}  // namespace atlas::sonar_eval
