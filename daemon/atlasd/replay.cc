#include "daemon/atlasd/replay.h"

#include <sys/stat.h>

#include <cerrno>
#include <cstdio>
#include <cstring>
#include <lcm/lcm-cpp.hpp>

#include "daemon/atlasd/daemon_setup.h"
#include "daemon/lcm_out/lcm_convert.h"

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
  lcm::LogFile log(log_path, "r");
  if (!log.good()) {
    std::fprintf(stderr, "atlasd: cannot read the LCM log %s (%s)\n", log_path.c_str(),
                 std::strerror(errno));
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
  int64_t events = 0, bad = 0, scans = 0, sonar = 0, used = 0;
  // Decodes the event as M; counts it as undecodable when it is not one.
  auto decode = [&bad](const lcm::LogEvent& e, auto* m) {
    if (m->decode(e.data, 0, e.datalen) >= 0) return true;
    ++bad;
    return false;
  };
  auto step = [&] {
    loop.StepAll(&sink);
    if (++used % 2000 == 0)
      std::fprintf(stderr, "atlasd: replay: %lld scans and readings\n",
                   static_cast<long long>(used));
  };
  while (const lcm::LogEvent* e = log.readNextEvent()) {
    ++events;
    if (atlas::odometry_t m; e->channel == ch.raw_odometry && decode(*e, &m)) {
      loop.AddOdometry(FromOdometryMessage(m));
    } else if (atlas::laser_scan_t m; e->channel == ch.raw_laser && decode(*e, &m)) {
      ++scans;
      if (maps_use == LocalMapSensors::kSonar) continue;
      loop.AddScan(FromLaserMessage(m));
      step();
    } else if (atlas::sonar_t m; e->channel == ch.raw_sonar && decode(*e, &m)) {
      ++sonar;
      if (maps_use == LocalMapSensors::kLaser) continue;
      loop.AddSonar(FromSonarMessage(m));
      step();
    }
  }
  std::fclose(poses);
  const std::string summary_path = out_dir + "/summary.txt";
  if (FILE* s = std::fopen(summary_path.c_str(), "w")) {
    std::fprintf(s,
                 "events %lld\nundecodable %lld\nscans %lld\nsonar_readings %lld\nsteps %lld\n"
                 "frames %d\nedges %d\n",
                 static_cast<long long>(events), static_cast<long long>(bad),
                 static_cast<long long>(scans), static_cast<long long>(sonar),
                 static_cast<long long>(loop.steps()), atlas->Graph().FrameCount(),
                 atlas->Graph().EdgeCount());
    std::fclose(s);
  }
  std::fprintf(stderr,
               "atlasd: replay: %lld steps (%lld scans, %lld sonar readings in the log; "
               "localmap.sensors decides which are stepped), %d frames; %s\n",
               static_cast<long long>(loop.steps()), static_cast<long long>(scans),
               static_cast<long long>(sonar), atlas->Graph().FrameCount(), poses_path.c_str());
  return 0;
}

}  // namespace atlas
