#include "daemon/atlasd/reload.h"

#include <algorithm>

#include "daemon/atlasd/daemon_setup.h"
#include "formats/config/config_loader.h"

namespace atlas {
namespace {

bool IsAtlasKey(const std::string& key) {
  return key.rfind("atlas.", 0) == 0 || key.rfind("noise.", 0) == 0;
}

// Why the running atlas's image does not load into `rebuilt`, made with the new parameters.
std::string Misfit(const Atlas& running, const Atlas& rebuilt, int map_capacity) {
  std::string why;
  const auto add = [&why](const std::string& s) { why += (why.empty() ? "" : "; ") + s; };
  const AtlasOptions& o = rebuilt.Options();
  const int alive = static_cast<int>(running.Hypotheses().size());
  if (alive > o.max_hypotheses)
    add(std::to_string(alive) + " hypotheses alive, above atlas.max_hypotheses " +
        std::to_string(o.max_hypotheses));
  int features = 0;
  for (FrameId f = 0; f < running.Graph().FrameCount(); ++f)
    features = std::max(features, running.Graph().Frame(f).map->Complexity());
  size_t z = 0;
  for (const Hypothesis& h : running.Hypotheses()) {
    if (h.trial_map) features = std::max(features, h.trial_map->Complexity());
    z = std::max(z, h.z.size());
  }
  if (features > map_capacity)
    add("a map holds " + std::to_string(features) + " features, above atlas.map_capacity " +
        std::to_string(map_capacity) + " (a capacity can grow on reload, not shrink)");
  if (z >= static_cast<size_t>(o.lifecycle.probation_scans))
    add("a juvenile holds " + std::to_string(z) + " scans for w, not below its probation of " +
        std::to_string(o.lifecycle.probation_scans) + " steps");
  return why.empty() ? "hypotheses alive: " + std::to_string(alive) : why;
}

}  // namespace

ReloadPlan PlanReload(const DaemonOptions& running, const DaemonOptions& loaded) {
  ReloadPlan plan;
  const ReloadDiff diff = DiffForReload(running, loaded);
  for (const std::string& k : diff.reloadable) {
    if (IsAtlasKey(k)) {
      plan.atlas_keys.push_back(k);
    } else {
      plan.applied.push_back(k);
    }
  }
  plan.needs_restart = diff.needs_restart;
  plan.rebuild_atlas = !plan.atlas_keys.empty();
  DaemonOptions& next = plan.without_atlas;
  next = running;
  next.loop.step_budget_ms = loaded.loop.step_budget_ms;
  next.lcm.health_period_s = loaded.lcm.health_period_s;
  next.lcm.graph_period_s = loaded.lcm.graph_period_s;
  next.lcm.local_map_period_s = loaded.lcm.local_map_period_s;
  next.lcm.republish_raw = loaded.lcm.republish_raw;
  next.state.save_period_s = loaded.state.save_period_s;
  plan.with_atlas = next;
  plan.with_atlas.atlas = loaded.atlas;
  plan.with_atlas.noise = loaded.noise;
  return plan;
}

AtlasRebuild RebuildAtlas(const Atlas& running, const DaemonOptions& options) {
  AtlasRebuild out;
  out.settings = ToMapperSettings(options);
  if (std::string e = ValidateMapperSettings(out.settings); !e.empty()) {
    out.refused = e;
    return out;
  }
  std::unique_ptr<Atlas> rebuilt = MakeAtlas(out.settings);
  if (!rebuilt->Deserialize(running.Serialize())) {
    out.refused = "the running atlas does not fit the new parameters (" +
                  Misfit(running, *rebuilt, out.settings.local_map.capacity) + ")";
    return out;
  }
  out.atlas = std::move(rebuilt);
  return out;
}

std::string ReloadReport(const ReloadPlan& plan, const std::string& atlas_refused) {
  std::string applied, restart, refused;
  for (const std::string& k : plan.applied) applied += " " + k;
  if (atlas_refused.empty()) {
    for (const std::string& k : plan.atlas_keys) applied += " " + k;
  } else {
    refused = " atlas/noise parameters refused (" + atlas_refused + "), the running ones stay;";
  }
  for (const std::string& k : plan.needs_restart) restart += " " + k;
  return "reload: applied:" + (applied.empty() ? std::string(" (nothing)") : applied) + ";" +
         refused + (restart.empty() ? "" : " need a restart (unchanged until then):" + restart);
}

}  // namespace atlas
