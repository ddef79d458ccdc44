#pragma once
// The live atlasd (docs/atlasd.md): device reader threads -> fixed-capacity queues -> one loop
// thread (loop_thread.h: drain, steps, LCM output, health, checkpoints, reloads) -> LCM. This is
// the process shell, on the main thread:
// - signals: SIGTERM/SIGINT stop, SIGHUP reloads the configuration file (reload.h; a file that
//   does not load changes nothing), SIGUSR1 stalls the loop for stall_seconds when
//   debug_stall_on_usr1 (tests of the watchdog); all are blocked in every other thread.
// - sd_notify (live_timing.h): READY=1 once the devices are open (or after ready_timeout, with
//   the missing devices in STATUS) and the loop runs; WATCHDOG=1 at half the watchdog interval
//   only while the loop thread's heartbeat is fresh; STATUS= the one-line summary; STOPPING=1.
//
// RunLiveDaemon() returns the process exit code: 0 after a clean stop, 1 when LCM cannot be
// opened, kExitConfigError for options ValidateDerivedOptions refuses, 70 (EX_SOFTWARE) when
// the loop thread stopped on an internal error (the store keeps the last checkpoint).

#include <string>

#include "formats/config/daemon_options.h"

namespace atlas {

struct LiveFlags {
  std::string config_path;          // for SIGHUP reloads
  double health_line_period_s = 0;  // stderr health line; 0: lcm.health_period_s
  bool quiet = false;               // no health line
  // SIGUSR1 stalls the loop thread for stall_seconds (tests of the watchdog). Off by default.
  bool debug_stall_on_usr1 = false;
  double stall_seconds = 5.0;
  double ready_timeout_s = 5.0;
};

int RunLiveDaemon(const DaemonOptions& options, const LiveFlags& flags);

}  // namespace atlas
