#pragma once
// The events a replay steps, from either kind of log (docs/formats.md): a CARMEN log (plain or
// gzip; drivers/carmen, ODOM and laser lines) or an lcm-logger file (daemon/lcm_log; the raw
// channels a session recorded with lcm.republish_raw = true: odometry, laser scans, sonar
// readings). The kind is told by the file's first bytes (an LCM log begins with its sync word).

#include <string>
#include <vector>

#include "core/common/sensor_types.h"
#include "formats/config/daemon_options.h"
#include "logs/carmen/carmen_log.h"
#include "replay/replay_run.h"

namespace atlas::replay {

struct LcmRawChannels {
  std::string odometry, laser, sonar;
};

struct ReplaySource {
  std::vector<SensorEvent> events;  // in log order
  bool lcm = false;                 // an lcm-logger file (else a CARMEN log)
  carmen::CarmenLog carmen;         // a CARMEN log as read (corrected logs: its reference)
  int64_t lcm_events = 0;           // events in an LCM log, any channel
  // An LCM log cut or damaged, or events on the raw channels that do not decode: the events
  // before the problem are replayed, and the replay is not of the whole session.
  std::vector<std::string> problems;
  std::string error;  // nothing could be read ("PATH: why")
};

// `progress` (optional): bytes of the file read so far and its size, now and then.
ReplaySource ReadReplaySource(const std::string& path, const carmen::CarmenLogOptions& carmen,
                              const LcmRawChannels& channels,
                              const carmen::ReadProgress& progress = {});

// The raw channels of atlasd's configuration (lcm.channels.raw_*).
LcmRawChannels RawChannels(const LcmChannels& channels);

// The exit code of a finished replay of `source` (the files are written): 1, after a message on
// stderr for each, when the log was not read whole (an LCM log cut, damaged or with undecodable
// events) or when nothing was stepped; else 0. A CARMEN log whose largest range looks like a
// no-return value read as returns (carmen::ClampNote) gets a note on stderr; the code stays.
int ReplayVerdict(const std::string& log_path, const ReplaySource& source,
                  const ReplayResult& result, const char* tool);

}  // namespace atlas::replay
