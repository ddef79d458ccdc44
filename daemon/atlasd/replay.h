#pragma once
// Offline replay (issue 6, "Offline replay from LCM logs"): the raw channels of an lcm-logger
// file (lcm.channels.raw_odometry / raw_laser / raw_sonar, recorded with lcm.republish_raw =
// true) go through the same StepLoop as a live run, in log order, each scan or sonar reading
// stepped as soon as it is read; the scans and readings stepped are those the configuration's
// local maps use (localmap.sensors), as live. The live loop adds items to its StepLoop in the
// order it republishes them and the StepLoop steps in the order of the Add calls
// (step_loop.h), so a complete recording of a session in which live dropped nothing replays to
// the same steps.
// Output in DIR:
//   poses.txt    one line per step: "t x y theta frame q" (t: seconds of the robot's clock;
//                pose in the dominant frame's coordinates)
//   summary.txt  events, scans and sonar readings read, steps, frames, edges
// Returns the exit code (0, or 1 with a message when the log cannot be read).

#include <string>

#include "daemon/config/daemon_options.h"

namespace atlas {

int RunReplay(const DaemonOptions& options, const std::string& log_path,
              const std::string& out_dir);

}  // namespace atlas
