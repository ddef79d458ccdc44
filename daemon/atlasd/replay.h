#pragma once
// `atlasd --replay LOG --out DIR`: the log through the one replay of atlas-replay
// (replay/replay_run.h), with the mapper and step loop of atlasd's configuration, writing the
// same output directory (docs/formats.md, "Replay output"); byte-identical to atlas-replay's for
// the same log and configuration file, except the measured step times. LOG is an lcm-logger
// file (the raw channels lcm.channels.raw_odometry / raw_laser / raw_sonar of a session recorded
// with lcm.republish_raw = true) or a CARMEN log (replay/replay_source.h). Of an lcm-logger file
// each scan or sonar reading is stepped as soon as it is read, in log order; the live loop adds
// items to its StepLoop in the order it republishes them and the StepLoop steps in the order of
// the Add calls (step_loop.h), so a complete recording of a session in which live dropped
// nothing replays to the same steps. Returns the exit code: 0; 1 with a message when the log
// cannot be read (nothing is written), when an LCM log is truncated or corrupt or holds events
// on the raw channels that do not decode (the output then holds the steps of the events read),
// when it holds nothing to step, or when the output cannot be written.

#include <string>

#include "formats/config/daemon_options.h"

namespace atlas {

int RunReplay(const DaemonOptions& options, const std::string& log_path,
              const std::string& out_dir);

}  // namespace atlas
