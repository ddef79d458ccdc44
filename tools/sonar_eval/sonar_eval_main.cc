// atlas-sonar-eval: evaluation of sonar-only line mapping; one file per mode (mc_mode.h,
// fig9_mode.h, atlas_mode.h, assoc_mode.h).

#include "tools/cli/tool_modes.h"
#include "tools/sonar_eval/assoc_mode.h"
#include "tools/sonar_eval/atlas_mode.h"
#include "tools/sonar_eval/fig9_mode.h"
#include "tools/sonar_eval/mc_mode.h"

namespace {

constexpr char kUsage[] =
    "Evaluation of sonar-only line mapping on the simulator. 'atlas-sonar-eval MODE --help'\n"
    "lists a mode's options with their defaults. The maps are atlasd's with the simulated\n"
    "hardware's noise models, and the atlases atlasd's for each sensor alone\n"
    "(sonar_atlas_run.h).\n"
    "\n"
    "mc:   simulated 20 m corridor, robot driving back and forth; on each seeded run a sonar-only\n"
    "      and a laser-only local map (same odometry). Prints the robot NEES (3 dof) against its\n"
    "      95 % band, the NEES of each sonar line at its initialisation against the nearest true\n"
    "      wall (2 dof, and 5 dof with the robot pose), and relative-pose errors over pairs 5, 30\n"
    "      and 90 s apart for sonar, laser and dead reckoning.\n"
    "atlas: N simulated runs (noise seeds S..S+N-1) with laser and sonar through a world: the\n"
    "      building with corridor loops of atlas-sim (R rooms, layout from --seed), or 'alcoves':\n"
    "      one L x W corridor loop with an alcove every P metres (repetitive structure: Condition\n"
    "      2). On each run a sonar-only atlas (SonarLocalMap) and a laser-only atlas (LineEkfMap;\n"
    "      --laser 0: none). Prints frames, map-matching outcomes by reason (accepted / refused\n"
    "      as ambiguous / rejected), every map-match edge against the ground truth (chi-square\n"
    "      3 dof > 14.16: false closure), also as map-matching made it (before edge refinement),\n"
    "      the robot NEES of the dominant pose in its frame averaged over the runs against its\n"
    "      95 % band, and relative-pose errors (5 s, 30 s) next to dead reckoning. --trace FILE:\n"
    "      one row per step and live hypothesis (its pose error, and its map's lines against the\n"
    "      true walls). --sonar-w 0: the sonar atlas without w (eq. 12; SonarMapBootstrapper):\n"
    "      its juveniles keep their seeded pose and trial map.\n"
    "assoc: one sonar-only local map (no atlas) through the world: every return the map applied\n"
    "      to a feature is checked against the wall the simulator echoed it from (in-cone and\n"
    "      edge-of-cone pairings: the true wall's line, another line, or no wall: multipath);\n"
    "      the first N wrong pairings are listed; NEES every 10 s.\n"
    "fig9: the returns, vantage points and lines of the first K sonar feature initialisations\n"
    "      (map-frame, estimated poses) over the true walls, like the paper's Fig. 9, in the\n"
    "      corridor of mc. --phantoms 1: only lines farther than 0.25 m or 10 deg from every\n"
    "      wall (mc's count); --minutes M: how long to drive for them.\n";

}  // namespace

int main(int argc, char** argv) {
  namespace se = atlas::sonar_eval;
  return atlas::cli::RunToolMode(argc, argv, "atlas-sonar-eval", kUsage,
                                 {se::McMode(), se::AtlasMode(), se::AssocMode(), se::Fig9Mode()});
}
