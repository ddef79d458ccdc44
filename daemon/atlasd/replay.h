#pragma once
// Offline replay (issue 6, "Offline replay from LCM logs"): the raw channels of an lcm-logger
// file (lcm.channels.raw_*, recorded with lcm.republish_raw = true) go through the same
// StepLoop as a live run, in log order: odometry samples into the track, each scan stepped
// once the events before it are in. Output in DIR:
//   poses.txt    one line per step: "t x y theta frame q" (t: seconds of the robot's clock;
//                pose in the dominant frame's coordinates)
//   summary.txt  steps, frames, edges, hypotheses
// Returns the exit code (0, or 1 with a message when the log cannot be read).

#include <string>

#include "daemon/config/daemon_options.h"

namespace atlas {

int RunReplay(const DaemonOptions& options, const std::string& log_path,
              const std::string& out_dir);

}  // namespace atlas
