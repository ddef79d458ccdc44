#include "daemon/atlasd/reload.h"

#include <gtest/gtest.h>

#include <map>
#include <string>

#include "core/testing/fake_wall_scanner.h"
#include "daemon/atlasd/daemon_setup.h"
#include "formats/config/config_loader.h"
#include "sim/corridor.h"

namespace atlas {
namespace {

// A configuration that differs from the defaults in keys of every kind: applied at once,
// applied by rebuilding the atlas, and needing a restart.
DaemonOptions Changed() {
  DaemonOptions o;
  o.lcm.graph_period_s += 1.0;
  o.lcm.republish_raw = !o.lcm.republish_raw;
  o.loop.step_budget_ms += 1.0;
  o.state.save_period_s += 1.0;
  o.atlas.max_hypotheses += 1;
  o.noise.laser.range_sigma_m *= 2.0;
  o.laser.device = "/dev/ttyS7";
  o.lcm.url = "udpm://239.255.76.67:7668?ttl=0";
  o.loop.max_pending_scans += 1;
  return o;
}

// After a reload each key holds the loaded value when a running atlasd may change it
// (IsReloadableKey), else the running one.
TEST(Reload, TakesExactlyTheReloadableKeys) {
  const DaemonOptions running, loaded = Changed();
  const ReloadPlan plan = PlanReload(running, loaded);
  const auto before = FlattenOptions(running), after = FlattenOptions(loaded),
             with = FlattenOptions(plan.with_atlas), without = FlattenOptions(plan.without_atlas);
  for (const auto& [key, value] : before) {
    SCOPED_TRACE(key);
    EXPECT_EQ(with.at(key), IsReloadableKey(key) ? after.at(key) : value);
    const bool atlas_key = key.rfind("atlas.", 0) == 0 || key.rfind("noise.", 0) == 0;
    EXPECT_EQ(without.at(key), IsReloadableKey(key) && !atlas_key ? after.at(key) : value);
  }
  EXPECT_TRUE(plan.rebuild_atlas);
  EXPECT_EQ(plan.applied, (std::vector<std::string>{"lcm.graph_period_s", "lcm.republish_raw",
                                                    "loop.step_budget_ms", "state.save_period_s"}));
  EXPECT_EQ(plan.atlas_keys,
            (std::vector<std::string>{"atlas.max_hypotheses", "noise.laser.range_sigma_m"}));
  EXPECT_EQ(plan.needs_restart,
            (std::vector<std::string>{"laser.device", "lcm.url", "loop.max_pending_scans"}));
}

TEST(Reload, UnchangedAtlasParametersNeedNoRebuild) {
  DaemonOptions running, loaded;
  loaded.lcm.local_map_period_s += 0.5;
  const ReloadPlan plan = PlanReload(running, loaded);
  EXPECT_FALSE(plan.rebuild_atlas);
  EXPECT_TRUE(plan.atlas_keys.empty());
  EXPECT_DOUBLE_EQ(plan.with_atlas.lcm.local_map_period_s, loaded.lcm.local_map_period_s);
  EXPECT_EQ(ReloadReport(plan, ""), "reload: applied: lcm.local_map_period_s;");
  EXPECT_EQ(ReloadReport(PlanReload(running, running), ""), "reload: applied: (nothing);");
}

TEST(Reload, ReportSaysWhatWasAppliedRefusedAndWaitsForARestart) {
  const ReloadPlan plan = PlanReload(DaemonOptions(), Changed());
  EXPECT_EQ(ReloadReport(plan, ""),
            "reload: applied: lcm.graph_period_s lcm.republish_raw loop.step_budget_ms "
            "state.save_period_s atlas.max_hypotheses noise.laser.range_sigma_m; need a restart "
            "(unchanged until then): laser.device lcm.url loop.max_pending_scans");
  EXPECT_EQ(ReloadReport(plan, "too small"),
            "reload: applied: lcm.graph_period_s lcm.republish_raw loop.step_budget_ms "
            "state.save_period_s; atlas/noise parameters refused (too small), the running ones "
            "stay; need a restart (unchanged until then): laser.device lcm.url "
            "loop.max_pending_scans");
}

// An atlas that has mapped a corridor with the laser: its maps hold several lines.
std::unique_ptr<Atlas> MappedAtlas(const DaemonOptions& o) {
  std::unique_ptr<Atlas> atlas = MakeAtlas(ToMapperSettings(o));
  FakeLaserOptions laser;
  laser.beams = 181;
  FakeWallScanner scanner(sim::CorridorWalls(), laser, 7);
  for (int i = 0; i < 40; ++i) atlas->Step(Pose2{0.05, 0.0, 0.0}, scanner.Scan({0.05 * i, 0, 0}));
  return atlas;
}

int MostFeatures(const Atlas& a) {
  int n = 0;
  for (FrameId f = 0; f < a.Graph().FrameCount(); ++f)
    n = std::max(n, a.Graph().Frame(f).map->Complexity());
  return n;
}

TEST(Reload, RebuiltAtlasKeepsGraphMapsAndHypotheses) {
  for (const LocalMapKind kind : {LocalMapKind::kGrid, LocalMapKind::kLines}) {
    DaemonOptions running;
    running.localmap.kind = kind;
    const std::unique_ptr<Atlas> atlas = MappedAtlas(running);
    ASSERT_GE(MostFeatures(*atlas), 2);
    DaemonOptions loaded = running;
    loaded.atlas.map_capacity = running.atlas.map_capacity + 10;
    loaded.noise.odometry.wheel_sigma_per_m *= 2.0;
    const AtlasRebuild r = RebuildAtlas(*atlas, PlanReload(running, loaded).with_atlas);
    ASSERT_NE(r.atlas, nullptr) << r.refused;
    EXPECT_TRUE(r.refused.empty());
    EXPECT_EQ(r.settings.local_map.capacity, loaded.atlas.map_capacity);
    EXPECT_EQ(r.atlas->StepCount(), atlas->StepCount());
    EXPECT_EQ(r.atlas->Hypotheses().size(), atlas->Hypotheses().size());
    EXPECT_TRUE(r.atlas->Serialize() == atlas->Serialize());
  }
}

// Line maps hold at most atlas.map_capacity lines (a grid frame's capacity is its own scans).
TEST(Reload, RebuildIsRefusedWhenTheAtlasDoesNotFit) {
  DaemonOptions running;
  running.localmap.kind = LocalMapKind::kLines;
  const std::unique_ptr<Atlas> atlas = MappedAtlas(running);
  const int features = MostFeatures(*atlas);
  ASSERT_GE(features, 2);
  DaemonOptions loaded = running;
  loaded.atlas.map_capacity = features - 1;
  const AtlasRebuild r = RebuildAtlas(*atlas, PlanReload(running, loaded).with_atlas);
  EXPECT_EQ(r.atlas, nullptr);
  EXPECT_EQ(r.refused, "the running atlas does not fit the new parameters (a map holds " +
                           std::to_string(features) + " features, above atlas.map_capacity " +
                           std::to_string(features - 1) +
                           " (a capacity can grow on reload, not shrink))");
}

TEST(Reload, RebuildIsRefusedForInvalidMapperSettings) {
  const DaemonOptions running;
  const std::unique_ptr<Atlas> atlas = MappedAtlas(running);
  DaemonOptions loaded = running;
  loaded.atlas.max_sigma_x = -1.0;
  const AtlasRebuild r = RebuildAtlas(*atlas, loaded);
  EXPECT_EQ(r.atlas, nullptr);
  EXPECT_EQ(r.refused, ValidateMapperSettings(ToMapperSettings(loaded)));
  EXPECT_FALSE(r.refused.empty());
}

}  // namespace
}  // namespace atlas
