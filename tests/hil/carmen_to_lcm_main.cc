// atlas-carmen-to-lcm: a CARMEN log as an lcm-logger file of atlasd's raw channels, for the
// hardware-in-loop test of the LCM input (tests/hil/lcm_input_matches_replay.sh). See --help.
#include <algorithm>
#include <cinttypes>
#include <cmath>
#include <cstdio>
#include <lcm/lcm-cpp.hpp>
#include <limits>
#include <optional>
#include <string>
#include <vector>

#include "bot_core/planar_lidar_t.hpp"
#include "bot_core/pose_t.hpp"
#include "daemon/lcm_out/lcm_convert.h"
#include "drivers/fake/playback.h"
#include "tools/cli/command_line.h"

namespace {

constexpr const char* kDescription =
    R"(Writes the scans of a CARMEN log as atlasd.laser_scan_t and its odometry as atlasd.odometry_t
(--types atlas), or as libbot's bot_core.planar_lidar_t and bot_core.pose_t (--types bot_core:
the scanner's mount is then not in the messages), into an lcm-logger file, each event at its log
time (utime and event timestamp: the log's stamp in microseconds), for lcm-logplayer. The
odometry is the log's, linearly interpolated at --odometry-rate-hz, as a base reports it (the
fake AgileX base of atlas-fakedev sends 50 Hz), or the log's own samples with 0.)";

constexpr const char* kFooter =
    R"(Prints "scans=N odometry=M first_s=T0 last_s=T1" on stdout. Exit 0; 1 when the log cannot be
read or the output written; 2 on a usage error.
)";

struct Event {
  atlas::Time stamp;
  std::string channel;
  std::vector<uint8_t> data;
};

template <typename M>
Event Encode(atlas::Time stamp, const std::string& channel, const M& m) {
  Event e{stamp, channel, std::vector<uint8_t>(static_cast<size_t>(m.getEncodedSize()))};
  m.encode(e.data.data(), 0, static_cast<int>(e.data.size()));
  return e;
}

bot_core::planar_lidar_t ToPlanarLidar(const atlas::LaserScan& s) {
  bot_core::planar_lidar_t m{};
  m.utime = atlas::ToUtime(s.stamp);
  m.nranges = static_cast<int32_t>(s.ranges.size());
  m.ranges = s.ranges;
  m.nintensities = 0;
  m.rad0 = s.angle_min;
  m.radstep = s.angle_increment;
  return m;
}

bot_core::pose_t ToBotPose(atlas::Time t, const atlas::Pose2& p) {
  bot_core::pose_t m{};
  m.utime = atlas::ToUtime(t);
  m.pos[0] = p.x;
  m.pos[1] = p.y;
  m.orientation[0] = std::cos(p.theta / 2);
  m.orientation[3] = std::sin(p.theta / 2);
  return m;
}

}  // namespace

int main(int argc, char** argv) {
  std::string log_path, out_path, types = "atlas", laser_channel = "ATLAS_RAW_LASER",
                                  odometry_channel = "ATLAS_RAW_ODOMETRY";
  int64_t max_scans = 0;
  double odometry_rate_hz = 50.0;
  atlas::cli::CommandLine command_line("atlas-carmen-to-lcm",
                                       {"atlas-carmen-to-lcm LOG --out FILE [options]"},
                                       kDescription, kFooter);
  CLI::App& app = command_line.app();
  atlas::cli::AddPositional(app, "LOG", &log_path, "a CARMEN log (plain or gzip)");
  atlas::cli::AddText(app, "--out", "FILE", &out_path, "the lcm-logger file to write (required)");
  atlas::cli::AddInteger(app, "--max-scans", "N", 0, std::numeric_limits<int64_t>::max(),
                         &max_scans, "only the first N scans (default 0: all)");
  atlas::cli::AddNumber(app, "--odometry-rate-hz", "HZ", 0, 1000, &odometry_rate_hz,
                        "odometry samples per second of log time, 0: the log's own (default 50)");
  atlas::cli::AddChoice(app, "--types", "TYPES", {"atlas", "bot_core"}, &types,
                        "the message types: atlas or bot_core (default atlas)");
  atlas::cli::AddText(app, "--laser-channel", "NAME", &laser_channel,
                      "channel of the scans (default ATLAS_RAW_LASER)");
  atlas::cli::AddText(app, "--odometry-channel", "NAME", &odometry_channel,
                      "channel of the odometry (default ATLAS_RAW_ODOMETRY)");
  if (std::optional<int> done = command_line.Parse(argc, argv)) return *done;
  if (log_path.empty()) return command_line.Usage("no LOG given");
  if (out_path.empty()) return command_line.Usage("--out FILE is required");

  atlas::fake::Recording rec;
  std::string error;
  if (!atlas::fake::LoadCarmenRecording(log_path, static_cast<size_t>(max_scans), &rec, &error)) {
    std::fprintf(stderr, "atlas-carmen-to-lcm: %s\n", error.c_str());
    return 1;
  }
  std::vector<Event> events;
  const bool bot_core = types == "bot_core";
  for (const atlas::LaserScan& s : rec.scans) {
    events.push_back(bot_core ? Encode(s.stamp, laser_channel, ToPlanarLidar(s))
                              : Encode(s.stamp, laser_channel, atlas::ToLaserMessage(s)));
  }
  size_t odometry = 0;
  const auto add_odometry = [&](atlas::Time t, const atlas::Pose2& pose) {
    atlas::OdometrySample o;
    o.stamp = t;
    o.pose = pose;
    events.push_back(bot_core ? Encode(t, odometry_channel, ToBotPose(t, pose))
                              : Encode(t, odometry_channel, atlas::ToOdometryMessage(o)));
    ++odometry;
  };
  if (odometry_rate_hz > 0) {
    const atlas::Duration period(static_cast<int64_t>(1e9 / odometry_rate_hz));
    for (atlas::Time t = rec.begin; t <= rec.end; t += period) add_odometry(t, rec.OdometryAt(t));
  } else {
    for (const atlas::OdometrySample& o : rec.odometry) add_odometry(o.stamp, o.pose);
  }
  // In time order; an odometry sample before a scan of the same stamp (the loop's order).
  std::stable_sort(events.begin(), events.end(), [&](const Event& a, const Event& b) {
    if (a.stamp != b.stamp) return a.stamp < b.stamp;
    return a.channel == odometry_channel && b.channel != odometry_channel;
  });

  lcm::LogFile out(out_path, "w");
  if (!out.good()) {
    std::fprintf(stderr, "atlas-carmen-to-lcm: cannot write %s\n", out_path.c_str());
    return 1;
  }
  int64_t n = 0;
  for (Event& e : events) {
    lcm::LogEvent le;
    le.eventnum = n++;
    le.timestamp = atlas::ToUtime(e.stamp);
    le.channel = e.channel;
    le.datalen = static_cast<int32_t>(e.data.size());
    le.data = e.data.data();
    if (out.writeEvent(&le) != 0) {
      std::fprintf(stderr, "atlas-carmen-to-lcm: cannot write %s\n", out_path.c_str());
      return 1;
    }
  }
  std::printf("scans=%zu odometry=%zu first_s=%.6f last_s=%.6f\n", rec.scans.size(), odometry,
              atlas::ToSeconds(rec.begin), atlas::ToSeconds(rec.end));
  return 0;
}
