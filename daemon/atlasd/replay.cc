#include "daemon/atlasd/replay.h"

#include <sys/stat.h>

#include <cerrno>
#include <cstdio>
#include <cstring>
#include <map>

#include "daemon/atlasd/daemon_setup.h"
#include "daemon/lcm_out/lcm_convert.h"
#include "logs/lcm/lcm_log_reader.h"

namespace atlas {
namespace {

class PoseFileSink final : public StepSink {
 public:
  explicit PoseFileSink(FILE* f) : f_(f) {}
  void OnPose(Time stamp, const DominantOutput& d, PoseSource source) override {
    if (source != PoseSource::kScan) return;
    std::fprintf(f_, "%.6f %.6f %.6f %.6f %d %.4f\n", ToSeconds(stamp), d.pose.mean.x,
                 d.pose.mean.y, d.pose.mean.theta, d.valid ? d.frame : -1, d.valid ? d.q : 0.0);
  }
  void OnStep(Time, const Atlas&) override {}

 private:
  FILE* f_;
};

}  // namespace

int RunReplay(const DaemonOptions& options, const std::string& log_path,
              const std::string& out_dir) {
  if (std::string e = ValidateDerivedOptions(options); !e.empty()) {
    std::fprintf(stderr, "atlasd: configuration rejected:\n%s", e.c_str());
    return 78;
  }
  LcmLogReader log;
  if (!log.Open(log_path)) {
    std::fprintf(stderr, "atlasd: replay: %s\n", log.error().c_str());
    return 1;
  }
  if (mkdir(out_dir.c_str(), 0755) != 0 && errno != EEXIST) {
    std::fprintf(stderr, "atlasd: cannot create %s (%s)\n", out_dir.c_str(), std::strerror(errno));
    return 1;
  }
  const std::string poses_path = out_dir + "/poses.txt";
  FILE* poses = std::fopen(poses_path.c_str(), "w");
  if (poses == nullptr) {
    std::fprintf(stderr, "atlasd: cannot write %s (%s)\n", poses_path.c_str(),
                 std::strerror(errno));
    return 1;
  }
  std::fprintf(poses, "# atlasd --replay %s: t x y theta frame q\n", log_path.c_str());
  const MapperSettings settings = ToMapperSettings(options);
  std::unique_ptr<Atlas> atlas = MakeAtlas(settings);
  StepLoopOptions loop_options = ToStepLoopOptions(options);
  loop_options.max_pending_scans = 64;  // offline: nothing is dropped (items are stepped at once)
  StepLoop loop(loop_options, settings, atlas.get());
  PoseFileSink sink(poses);
  const LocalMapSensors maps_use = options.localmap.sensors;
  const LcmChannels& ch = options.lcm.channels;
  int64_t scans = 0, sonar = 0, used = 0;
  std::map<std::string, int64_t> channels;  // events by channel (for the message below)
  auto step = [&] {
    loop.StepAll(&sink);
    if (++used % 2000 == 0)
      std::fprintf(stderr, "atlasd: replay: %lld scans and readings\n",
                   static_cast<long long>(used));
  };
  LcmLogEvent e;
  while (log.Next(&e)) {
    ++channels[e.channel];
    if (atlas::odometry_t m; e.channel == ch.raw_odometry && log.Decode(e, &m)) {
      loop.AddOdometry(FromOdometryMessage(m));
    } else if (atlas::laser_scan_t m; e.channel == ch.raw_laser && log.Decode(e, &m)) {
      ++scans;
      if (maps_use == LocalMapSensors::kSonar) continue;
      loop.AddScan(FromLaserMessage(m));
      step();
    } else if (atlas::sonar_t m; e.channel == ch.raw_sonar && log.Decode(e, &m)) {
      ++sonar;
      if (maps_use == LocalMapSensors::kLaser) continue;
      loop.AddSonar(FromSonarMessage(m));
      step();
    }
  }
  int rc = 0;
  // A write error (a full disk) shows at the latest when the file is closed.
  auto closed = [&rc](FILE* f, const std::string& path) {
    const bool ok = !std::ferror(f);
    if (std::fclose(f) == 0 && ok) return;
    std::fprintf(stderr, "atlasd: replay: cannot write %s (%s)\n", path.c_str(),
                 std::strerror(errno));
    rc = 1;
  };
  closed(poses, poses_path);
  const std::string summary_path = out_dir + "/summary.txt";
  if (FILE* s = std::fopen(summary_path.c_str(), "w")) {
    std::fprintf(s,
                 "events %lld\nundecodable %lld\nscans %lld\nsonar_readings %lld\nsteps %lld\n"
                 "frames %d\nedges %d\nlog %s\n",
                 static_cast<long long>(log.events()),
                 static_cast<long long>(log.undecodable_total()), static_cast<long long>(scans),
                 static_cast<long long>(sonar), static_cast<long long>(loop.steps()),
                 atlas->Graph().FrameCount(), atlas->Graph().EdgeCount(),
                 log.problem().empty() ? "complete" : (log.truncated() ? "truncated" : "corrupt"));
    closed(s, summary_path);
  } else {
    std::fprintf(stderr, "atlasd: replay: cannot write %s (%s)\n", summary_path.c_str(),
                 std::strerror(errno));
    rc = 1;
  }
  std::fprintf(stderr,
               "atlasd: replay: %lld steps (%lld scans, %lld sonar readings in the log; "
               "localmap.sensors decides which are stepped), %d frames; %s\n",
               static_cast<long long>(loop.steps()), static_cast<long long>(scans),
               static_cast<long long>(sonar), atlas->Graph().FrameCount(), poses_path.c_str());
  if (const std::vector<std::string> problems = log.Problems(); !problems.empty()) {
    // A cut or damaged recording (lcm-logger killed, disk full) is replayed up to the problem,
    // and the exit code says that the replay is not of the whole session.
    for (const std::string& p : problems) std::fprintf(stderr, "atlasd: replay: %s\n", p.c_str());
    std::fprintf(stderr,
                 "atlasd: replay: the output holds the steps of the events read; exit 1: the log "
                 "was not replayed whole\n");
    rc = 1;
  }
  if (used == 0) {
    std::string wanted, seen;
    if (maps_use != LocalMapSensors::kSonar) wanted = "scan on " + ch.raw_laser;
    if (maps_use != LocalMapSensors::kLaser)
      wanted += (wanted.empty() ? "" : " nor ") + ("sonar reading on " + ch.raw_sonar);
    for (const auto& [c, n] : channels) seen += " " + c + " (" + std::to_string(n) + ")";
    std::fprintf(stderr,
                 "atlasd: replay: %s: nothing to step: no %s, the items localmap.sensors names "
                 "(events by channel:%s). Record the session with lcm.republish_raw = true and "
                 "give its configuration file (localmap.sensors, lcm.channels)\n",
                 log_path.c_str(), wanted.c_str(), seen.empty() ? " none" : seen.c_str());
    rc = 1;
  }
  return rc;
}

}  // namespace atlas
