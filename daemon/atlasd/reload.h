#pragma once
// A configuration reload (SIGHUP) as data: what the running daemon takes from a newly loaded
// configuration (docs/atlasd.md, "Reload"). No I/O, no threads: the loop thread applies the plan.
//
// - The LCM periods, raw republishing, the step budget and the save period apply at once.
// - Atlas and noise parameters apply by rebuilding the running atlas from its own image with
//   the new settings (graph, maps and hypotheses kept). The rebuild is refused, and the running
//   atlas and its parameters kept, when the image does not fit them (Atlas::Deserialize bounds:
//   more hypotheses alive than atlas.max_hypotheses, a map above a smaller atlas.map_capacity,
//   a juvenile's w scans not below a shorter probation).
// - Every other changed key (devices, LCM URL and channels, state directory, capacities,
//   scheduling) waits for a restart (IsReloadableKey, config_loader.h).

#include <memory>
#include <string>
#include <vector>

#include "core/atlas/atlas.h"
#include "core/mapper/mapper_factory.h"
#include "formats/config/daemon_options.h"

namespace atlas {

struct ReloadPlan {
  // The options after the reload when the atlas takes the new atlas and noise parameters (or
  // when they did not change).
  DaemonOptions with_atlas;
  // The options after the reload when the rebuild is refused: the running atlas and noise.
  DaemonOptions without_atlas;
  bool rebuild_atlas = false;              // an atlas.* or noise.* key changed
  std::vector<std::string> applied;        // changed keys applied at once, in key order
  std::vector<std::string> atlas_keys;     // changed atlas.* and noise.* keys
  std::vector<std::string> needs_restart;  // changed keys that wait for a restart
};

ReloadPlan PlanReload(const DaemonOptions& running, const DaemonOptions& loaded);

// The running atlas rebuilt with `options`' mapper settings, or why not (`refused` not empty,
// `atlas` null).
struct AtlasRebuild {
  std::unique_ptr<Atlas> atlas;
  MapperSettings settings;
  std::string refused;
};
AtlasRebuild RebuildAtlas(const Atlas& running, const DaemonOptions& options);

// The one log line of a reload: what was applied, what was refused (`atlas_refused`: the
// rebuild's reason, empty when it was accepted or not needed) and what needs a restart.
std::string ReloadReport(const ReloadPlan& plan, const std::string& atlas_refused);

}  // namespace atlas
