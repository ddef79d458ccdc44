#include "daemon/atlasd/replay.h"

#include <cstdio>

#include "daemon/atlasd/daemon_setup.h"
#include "replay/replay_run.h"
#include "replay/replay_source.h"

namespace atlas {

int RunReplay(const DaemonOptions& options, const std::string& log_path,
              const std::string& out_dir) {
  if (std::string e = ValidateDerivedOptions(options); !e.empty()) {
    std::fprintf(stderr, "atlasd: configuration rejected:\n%s", e.c_str());
    return 78;
  }
  const replay::ReplaySource source = replay::ReadReplaySource(
      log_path, carmen::CarmenLogOptions{}, replay::RawChannels(options.lcm.channels));
  if (!source.error.empty()) {
    std::fprintf(stderr, "atlasd: replay: %s\n", source.error.c_str());
    return 1;
  }
  replay::ReplayOptions replay_options;
  replay_options.mapper = ToMapperSettings(options);
  replay_options.loop = ToStepLoopOptions(options);
  const replay::ReplayResult r = replay::RunReplay(source.events, replay_options, out_dir);
  if (!r.error.empty()) {
    std::fprintf(stderr, "atlasd: replay: %s\n", r.error.c_str());
    return 1;
  }
  std::fprintf(stderr,
               "atlasd: replay: %lld steps (%lld scans, %lld sonar readings; localmap.sensors "
               "decides which are stepped), %d frames, %d edges; %s\n",
               static_cast<long long>(r.summary.scans + r.summary.sonar_readings),
               static_cast<long long>(r.summary.scans),
               static_cast<long long>(r.summary.sonar_readings), r.summary.frames, r.summary.edges,
               out_dir.c_str());
  return replay::ReplayVerdict(log_path, source, r, "atlasd: replay");
}

}  // namespace atlas
