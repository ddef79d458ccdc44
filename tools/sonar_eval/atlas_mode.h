#pragma once
// atlas-sonar-eval atlas: N simulated runs (noise seeds S..S+N-1) with laser and sonar through
// a world (world_option.h); on each run a sonar-only atlas (SonarLocalMap) and a laser-only
// atlas (LineEkfMap), atlasd's for each sensor alone (SonarEvalAtlasOptions, sonar_atlas_run.h).
// Prints frames, map-matching outcomes by reason, every map-match edge against the ground truth
// (chi-square 3 dof > 14.16: false closure), the robot NEES of the dominant pose in its frame
// averaged over the runs against its 95 % band, and relative-pose errors (5 s, 30 s) next to dead
// reckoning (sonar_atlas_run.h).

#include "tools/cli/tool_modes.h"

namespace atlas::sonar_eval {

cli::ToolMode AtlasMode();

}  // namespace atlas::sonar_eval
