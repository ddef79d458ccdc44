// atlas-localmap-eval: evaluation of the line-feature EKF local map; one file per mode
// (mc_mode.h, real_mode.h).

#include "atlas_paths.h"
#include "tools/cli/tool_modes.h"
#include "tools/localmap_eval/mc_mode.h"
#include "tools/localmap_eval/real_mode.h"

namespace {

constexpr char kUsage[] =
    "Evaluation of the line-feature EKF local map. 'atlas-localmap-eval MODE --help' lists a\n"
    "mode's options with their defaults.\n"
    "\n"
    "mc:   Monte Carlo consistency of the line EKF in a simulated 20 m corridor (seeded runs of\n"
    "      M minutes each). Prints the 95 % chi-square band of the average NEES (robot: 3 dof;\n"
    "      features: joint NEES per dof) and the fraction of steps inside it, and the\n"
    "      simulator's odometry errors whitened with the filter's Q (per 50 Hz step and per\n"
    "      scan interval). --calibration: the base's wheel-radius / track-width errors are the\n"
    "      simulator's defaults in every run (fixed), drawn per run from the filter's sigmas\n"
    "      (per-run), or absent and not modelled (off). --per-run 1 prints each run's NEES at\n"
    "      the first scan, mean, max; --dump F writes every run's per-scan NEES to F.\n"
    "      The filter's range sigma is the simulator's (1 cm) times 1.05: the margin for the\n"
    "      line fits' residual biases. --set overrides filter\n"
    "      options as in real (--set range_sigma=0.01: the simulator's sigma exactly).\n"
    "real: mit-csail.clf.gz, one local map per stretch of M metres of travel, restarting at\n"
    "      each stretch (no Genesis). Scores the relations whose two poses lie in one stretch\n"
    "      and dead reckoning on the same relations. --png draws stretch K's map over its scans.\n"
    "      --laser-x: the laser X metres ahead of the robot's centre (the log's FLASER lines\n"
    "      give none). --set overrides filter options (a bad name lists them).\n"
    "      --laser-time-offset S: a scan was taken at its stamp + S seconds (-1..1; mit-csail:\n"
    "      about -0.1): the filter's odometry is interpolated there. Dead reckoning is the\n"
    "      log's odometry at the scan stamps (with S, also printed at stamp + S).\n"
    "      --scan-match 1 (default): the filter predicts with each scan matched against the one\n"
    "      before (core/scanmatch, atlasd's [scan_match] defaults) instead of the odometry\n"
    "      increment, as atlasd's loop does; 0: the odometry alone. Dead reckoning stays the\n"
    "      log's odometry.\n"
    "      Defaults: " ATLAS_SHARED_DIR "/datasets/mit-csail/mit-csail.clf.gz and .relations\n";

}  // namespace

int main(int argc, char** argv) {
  namespace le = atlas::localmap_eval;
  return atlas::cli::RunToolMode(argc, argv, "atlas-localmap-eval", kUsage,
                                 {le::McMode(), le::RealMode()});
}
