#pragma once
// The live atlasd: device reader threads -> fixed-capacity queues -> one loop thread (StepLoop)
// -> LCM; the main thread handles signals and systemd (docs/atlasd.md).
//
// Threads:
// - one reader thread per enabled device (drivers/device), each with its SPSC queue;
// - the loop thread: drains the queues (odometry first, then sonar, then scans), republishes
//   raw data when lcm.republish_raw, steps the atlas on the oldest pending scan, or sonar
//   reading when localmap.sensors maps with the sonar (older ones beyond
//   loop.max_pending_scans are dropped and counted; a sonar reading waits for the next wake-up,
//   at most 10 ms, as the sonar reader does not wake the loop), publishes the pose at every step,
//   the local map, graph and hypotheses at their periods, and health every
//   lcm.health_period_s; when idle it sleeps until the laser reader queues a scan (at most
//   10 ms, for dead reckoning and health), never polling and never blocking on a device. It runs
//   with the configured scheduling (policy, priority, affinity); when that is refused it
//   carries on with the default scheduling and a warning.
// - the main thread: signals (SIGTERM/SIGINT stop, SIGHUP reload, SIGUSR1 test stall when
//   enabled), sd_notify: READY=1 once the devices are open (or after ready_timeout, with the
//   missing devices in STATUS) and the loop runs; WATCHDOG=1 at half the watchdog interval only
//   while the loop thread's heartbeat is fresh; STATUS= the one-line summary; STOPPING=1.
//
// Run() returns the process exit code.

#include <string>

#include "daemon/config/daemon_options.h"

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
