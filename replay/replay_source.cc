#include "replay/replay_source.h"

#include <cstdio>

#include "daemon/lcm_out/lcm_convert.h"
#include "logs/lcm/lcm_log_reader.h"

namespace atlas::replay {
namespace {

// LCM's event log begins with the sync word 0xEDA1DA01 (big-endian).
bool BeginsWithLcmSyncWord(const std::string& path) {
  FILE* f = std::fopen(path.c_str(), "rb");
  if (f == nullptr) return false;
  unsigned char b[4] = {0, 0, 0, 0};
  const bool read = std::fread(b, 1, 4, f) == 4;
  std::fclose(f);
  return read && b[0] == 0xED && b[1] == 0xA1 && b[2] == 0xDA && b[3] == 0x01;
}

void ReadLcm(const std::string& path, const LcmRawChannels& ch,
             const carmen::ReadProgress& progress, ReplaySource* out) {
  LcmLogReader log;
  if (!log.Open(path)) {
    out->error = log.error();
    return;
  }
  LcmLogEvent e;
  while (log.Next(&e)) {
    if (progress && log.events() % 4096 == 0) progress(log.bytes_read(), log.size());
    if (atlasd::odometry_t m; e.channel == ch.odometry && log.Decode(e, &m)) {
      out->events.push_back(FromOdometryMessage(m));
    } else if (atlasd::laser_scan_t m; e.channel == ch.laser && log.Decode(e, &m)) {
      out->events.push_back(FromLaserMessage(m));
    } else if (atlasd::sonar_t m; e.channel == ch.sonar && log.Decode(e, &m)) {
      out->events.push_back(FromSonarMessage(m));
    }
  }
  if (progress) progress(log.bytes_read(), log.size());
  out->lcm_events = log.events();
  out->problems = log.Problems();
}

}  // namespace

ReplaySource ReadReplaySource(const std::string& path, const carmen::CarmenLogOptions& carmen,
                              const LcmRawChannels& channels,
                              const carmen::ReadProgress& progress) {
  ReplaySource out;
  out.lcm = BeginsWithLcmSyncWord(path);
  if (out.lcm) {
    ReadLcm(path, channels, progress, &out);
    return out;
  }
  carmen::CarmenReadResult read = carmen::ReadCarmenLog(path, carmen, progress);
  if (!read.ok()) {
    out.error = read.error;
    return out;
  }
  if (read.log.events.empty()) {
    out.error = path + ": no ODOM or laser lines (neither a CARMEN log nor an lcm-logger file?)";
    return out;
  }
  out.carmen = std::move(read.log);
  out.events.reserve(out.carmen.events.size());
  for (const carmen::CarmenEvent& e : out.carmen.events) out.events.push_back(e.event);
  return out;
}

LcmRawChannels RawChannels(const LcmChannels& channels) {
  return {channels.raw_odometry, channels.raw_laser, channels.raw_sonar};
}

int ReplayVerdict(const std::string& log_path, const ReplaySource& source,
                  const ReplayResult& result, const char* tool) {
  int rc = 0;
  if (const std::string note = source.lcm ? "" : carmen::ClampNote(source.carmen); !note.empty())
    std::fprintf(stderr, "%s: %s: %s\n", tool, log_path.c_str(), note.c_str());
  if (!source.problems.empty()) {
    // A cut or damaged recording (lcm-logger killed, disk full) is replayed up to the problem,
    // and the exit code says that the replay is not of the whole session.
    for (const std::string& p : source.problems) std::fprintf(stderr, "%s: %s\n", tool, p.c_str());
    std::fprintf(stderr,
                 "%s: the output holds the steps of the events read; exit 1: the log was not "
                 "replayed whole\n",
                 tool);
    rc = 1;
  }
  if (result.summary.scans + result.summary.sonar_readings == 0) {
    std::fprintf(
        stderr,
        "%s: %s: nothing to step: no scan or sonar reading that localmap.sensors names "
        "(%s). An lcm-logger file must hold the raw channels: record the session with "
        "lcm.republish_raw = true and give its configuration file (localmap.sensors, "
        "lcm.channels)\n",
        tool, log_path.c_str(),
        source.lcm ? (std::to_string(source.lcm_events) + " LCM events").c_str() : "a CARMEN log");
    rc = 1;
  }
  return rc;
}

}  // namespace atlas::replay
