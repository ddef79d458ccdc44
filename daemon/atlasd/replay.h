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
//   summary.txt  events, undecodable, scans and sonar readings read, steps, frames, edges, and
//                "log complete|truncated|corrupt"
// The log is read by LcmLogReader (logs/lcm). Returns the exit code: 0; 1 with a message
// when the log is not an LCM log (nothing is written), when it is truncated or corrupt or holds
// events on the raw channels that do not decode (the output then holds the steps of the events
// read), when it holds nothing to step, or when the output cannot be written.

#include <string>

#include "daemon/config/daemon_options.h"

namespace atlas {

int RunReplay(const DaemonOptions& options, const std::string& log_path,
              const std::string& out_dir);

}  // namespace atlas
