// atlas-lcm-log-summary: what an lcm-logger file of an atlasd session holds, as key=value
// lines for the hardware-in-loop test scripts (tests/hil/*.sh). See --help.
#include <cerrno>
#include <chrono>
#include <cinttypes>
#include <cstdio>
#include <cstring>
#include <map>
#include <optional>
#include <string>
#include <vector>

#include "atlasd/health_t.hpp"
#include "atlasd/laser_scan_t.hpp"
#include "atlasd/pose_t.hpp"
#include "bot_core/planar_lidar_t.hpp"
#include "formats/text_rows.h"
#include "formats/trajectory_tsv.h"
#include "logs/lcm/lcm_log_reader.h"
#include "tools/cli/command_line.h"

namespace {

constexpr const char* kDescription =
    R"(Prints key=value lines about an lcm-logger file recorded from atlasd (default channels):
  events.CHANNEL            messages per channel
  pose.count, pose.max_gap_s (largest gap between consecutive ATLAS_POSE receive times)
  health.count, health.laser_fault_seen (a status with LASER FAULT), health.last_steps,
  health.max_overruns, health.dropped_scans, health.version (atlasd's, in the last message),
  health.<driver>.<counter> (last value: bad_crc garbage_bytes truncated discontinuities
                             disconnects reconnects messages bad_messages queue_drops),
  health.<driver>.states (states seen, in order)
  undecodable.CHANNEL        ATLAS_POSE / ATLAS_HEALTH (and --scans' channel) events that did not
                            decode (left out)
  log                       complete, truncated or corrupt)";

constexpr const char* kFooter =
    R"(Exit 0; 1 when LOGFILE is not an LCM log (nothing printed), or is truncated or corrupt, or holds
events that do not decode (the lines above are then printed for the events read, and stderr
says what is wrong and where), or FILE cannot be written; 2 on a usage error.
)";

// Microseconds as seconds with six decimals, exactly (a utime since the epoch has 16 digits,
// at the limit of a double's).
std::string Seconds(int64_t us) {
  char b[32];
  std::snprintf(b, sizeof b, "%s%lld.%06lld", us < 0 ? "-" : "",
                static_cast<long long>((us < 0 ? -us : us) / 1000000),
                static_cast<long long>((us < 0 ? -us : us) % 1000000));
  return b;
}

}  // namespace

int main(int argc, char** argv) {
  std::string log_path, poses_path, trajectory_path, scans_path, scan_channel = "ATLAS_RAW_LASER";
  atlas::cli::CommandLine command_line(
      "atlas-lcm-log-summary",
      {"atlas-lcm-log-summary LOGFILE [--poses FILE] [--trajectory FILE] [--scans FILE]"},
      kDescription, kFooter);
  CLI::App& app = command_line.app();
  atlas::cli::AddPositional(app, "LOGFILE", &log_path, "an lcm-logger file");
  atlas::cli::AddText(app, "--poses", "FILE", &poses_path,
                      "write the poses received: \"t x y theta frame q r\" (t: utime in seconds,\n"
                      "r: the logger's receive time in seconds)");
  atlas::cli::AddText(app, "--scans", "FILE", &scans_path,
                      "write the laser scans (atlasd.laser_scan_t or bot_core.planar_lidar_t)\n"
                      "received on --scan-channel:\n"
                      "\"r t\" (r: the logger's receive time, t: utime, in seconds)");
  atlas::cli::AddText(app, "--scan-channel", "NAME", &scan_channel,
                      "the channel of --scans (default ATLAS_RAW_LASER)");
  atlas::cli::AddText(app, "--trajectory", "FILE", &trajectory_path,
                      "write the poses received with a frame as a replay's trajectory.tsv\n"
                      "(docs/formats.md): \"timestamp frame x y theta\"");
  if (std::optional<int> done = command_line.Parse(argc, argv)) return *done;
  auto Usage = [&](const std::string& what) { return command_line.Usage(what); };
  if (log_path.empty()) return Usage("no LOGFILE given");
  atlas::LcmLogReader log;
  if (!log.Open(log_path)) {
    std::fprintf(stderr, "atlas-lcm-log-summary: %s\n", log.error().c_str());
    return 1;
  }
  FILE* poses = nullptr;
  if (!poses_path.empty() && (poses = std::fopen(poses_path.c_str(), "w")) == nullptr) {
    std::fprintf(stderr, "atlas-lcm-log-summary: cannot write the poses file %s (%s)\n",
                 poses_path.c_str(), std::strerror(errno));
    return 1;
  }
  FILE* scans = nullptr;
  if (!scans_path.empty() && (scans = std::fopen(scans_path.c_str(), "w")) == nullptr) {
    std::fprintf(stderr, "atlas-lcm-log-summary: cannot write the scans file %s (%s)\n",
                 scans_path.c_str(), std::strerror(errno));
    return 1;
  }
  std::map<std::string, int64_t> events;
  int64_t pose_count = 0, health_count = 0, last_pose_ts = -1;
  double max_gap = 0;
  bool fault = false;
  atlasd::health_t last{};
  int64_t max_overruns = 0;
  std::map<std::string, std::string> states;
  std::vector<atlas::formats::FramePoseRow> trajectory;
  atlas::LcmLogEvent e;
  while (log.Next(&e)) {
    ++events[e.channel];
    if (e.channel == "ATLAS_POSE") {
      atlasd::pose_t p{};
      if (!log.Decode(e, &p)) continue;
      ++pose_count;
      if (last_pose_ts >= 0) max_gap = std::max(max_gap, (e.timestamp - last_pose_ts) * 1e-6);
      last_pose_ts = e.timestamp;
      if (poses)
        std::fprintf(poses, "%s %.6f %.6f %.6f %d %.4f %s\n", Seconds(p.utime).c_str(), p.x, p.y,
                     p.theta, p.frame_id, p.q, Seconds(e.timestamp).c_str());
      if (!trajectory_path.empty() && p.frame_id >= 0) {
        // Two scans read in one burst carry the burst's arrival stamp; trajectory.tsv holds one
        // pose per stamp (docs/formats.md): the later estimate stands.
        const atlas::formats::FramePoseRow row{atlas::Time(std::chrono::microseconds(p.utime)),
                                               p.frame_id, atlas::Pose2{p.x, p.y, p.theta}, 0};
        if (!trajectory.empty() && trajectory.back().stamp == row.stamp)
          trajectory.back() = row;
        else
          trajectory.push_back(row);
      }
    } else if (scans != nullptr && e.channel == scan_channel) {
      // atlasd.laser_scan_t, else bot_core.planar_lidar_t (counted when neither).
      atlasd::laser_scan_t m{};
      bot_core::planar_lidar_t b{};
      const int size = static_cast<int>(e.data.size());
      int64_t utime = 0;
      if (m.decode(e.data.data(), 0, size) >= 0) {
        utime = m.utime;
      } else if (log.Decode(e, &b)) {
        utime = b.utime;
      } else {
        continue;
      }
      std::fprintf(scans, "%s %s\n", Seconds(e.timestamp).c_str(), Seconds(utime).c_str());
    } else if (e.channel == "ATLAS_HEALTH") {
      atlasd::health_t h{};
      if (!log.Decode(e, &h)) continue;
      ++health_count;
      if (h.status.find("LASER FAULT") != std::string::npos) fault = true;
      max_overruns = std::max<int64_t>(max_overruns, h.overruns);
      for (const auto& d : h.drivers) {
        static const char* kNames[] = {"stopped", "connecting",   "running",
                                       "stalled", "reconnecting", "failed"};
        const std::string s = d.state >= 0 && d.state <= 5 ? kNames[d.state] : "?";
        std::string& seen = states[d.name];
        if (seen.empty() || seen.substr(seen.rfind(',') + 1) != s)
          seen += (seen.empty() ? "" : ",") + s;
      }
      last = h;
    }
  }
  int rc = 0;
  if (poses != nullptr) {
    const bool ok = !std::ferror(poses);
    if (std::fclose(poses) != 0 || !ok) {  // a full disk shows at the latest here
      std::fprintf(stderr, "atlas-lcm-log-summary: cannot write the poses file %s (%s)\n",
                   poses_path.c_str(), std::strerror(errno));
      rc = 1;
    }
  }
  if (scans != nullptr) {
    const bool ok = !std::ferror(scans);
    if (std::fclose(scans) != 0 || !ok) {
      std::fprintf(stderr, "atlas-lcm-log-summary: cannot write the scans file %s (%s)\n",
                   scans_path.c_str(), std::strerror(errno));
      rc = 1;
    }
  }
  if (!trajectory_path.empty()) {
    const std::string e = atlas::formats::WriteTextFile(
        trajectory_path,
        atlas::formats::FormatTrajectoryTsv(
            trajectory, "atlasd poses from ATLAS_POSE: timestamp frame x y theta"));
    if (!e.empty()) {
      std::fprintf(stderr, "atlas-lcm-log-summary: %s\n", e.c_str());
      rc = 1;
    }
  }
  for (const auto& [c, n] : events) std::printf("events.%s=%" PRId64 "\n", c.c_str(), n);
  std::printf("pose.count=%" PRId64 "\npose.max_gap_s=%.3f\n", pose_count, max_gap);
  std::printf("health.count=%" PRId64 "\nhealth.laser_fault_seen=%d\n", health_count, fault);
  std::printf("health.last_steps=%" PRId64 "\nhealth.max_overruns=%" PRId64
              "\nhealth.dropped_scans=%" PRId64 "\n",
              last.steps, max_overruns, last.dropped_scans);
  std::printf("health.num_frames=%d\n", last.num_frames);
  std::printf("health.version=%s\n", last.version.c_str());
  for (const auto& d : last.drivers) {
    const char* n = d.name.c_str();
    std::printf("health.%s.bad_crc=%" PRId64 "\nhealth.%s.garbage_bytes=%" PRId64
                "\nhealth.%s.truncated=%" PRId64 "\nhealth.%s.discontinuities=%" PRId64
                "\nhealth.%s.disconnects=%" PRId64 "\nhealth.%s.reconnects=%" PRId64
                "\nhealth.%s.messages=%" PRId64 "\nhealth.%s.bad_messages=%" PRId64
                "\nhealth.%s.queue_drops=%" PRId64 "\n",
                n, d.bad_crc, n, d.garbage_bytes, n, d.truncated, n, d.discontinuities, n,
                d.disconnects, n, d.reconnects, n, d.messages, n, d.bad_messages, n, d.queue_drops);
  }
  for (const auto& [n, s] : states) std::printf("health.%s.states=%s\n", n.c_str(), s.c_str());
  for (const auto& [c, n] : log.undecodable())
    std::printf("undecodable.%s=%" PRId64 "\n", c.c_str(), n);
  std::printf("log=%s\n", log.problem().empty() ? "complete"
                          : log.truncated()     ? "truncated"
                                                : "corrupt");
  if (const std::vector<std::string> problems = log.Problems(); !problems.empty()) {
    for (const std::string& p : problems)
      std::fprintf(stderr, "atlas-lcm-log-summary: %s\n", p.c_str());
    rc = 1;
  }
  return rc;
}
