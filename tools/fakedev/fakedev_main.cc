// atlas-fakedev: fake robot devices playing a CARMEN log as real device bytes.
// See --help.
#include <signal.h>
#include <sys/stat.h>

#include <atomic>
#include <cerrno>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <limits>
#include <memory>
#include <string>
#include <thread>

#include "core/common/parse_number.h"
#include "core/common/version.h"
#include "drivers/fake/fake_agilex_base.h"
#include "drivers/fake/fake_lms.h"
#include "drivers/fake/fake_p2os.h"
#include "drivers/fake/playback.h"

namespace {

constexpr const char* kHelp = R"(usage: atlas-fakedev --log FILE [options]

Fake robot devices for atlasd, playing a CARMEN log (plain or .gz) as real device bytes:
  laser     a SICK LMS 2xx on a pseudo-terminal (answers status, mode, variant and the baud
            switch; streams 0xB0 telegrams in continuous mode)
  odometry  an AgileX base on the fake CAN bus: a Unix SOCK_SEQPACKET socket, one struct
            can_frame per datagram (0x311 and 0x221 every 20 ms, 0x211 every 100 ms);
            point atlasd at  unix:PATH
  sonar     a Pioneer P2OS controller on a pseudo-terminal (SYNC handshake, OPEN, sonar on,
            SIPs every 100 ms with returns synthesised from the laser)
Run all devices in one process (default) or one per process (--only laser|odometry|sonar).

options:
  --log FILE             the CARMEN log to play (required)
  --speed F              playback speed, 1 = real time, 0.001..1000 (default 1)
  --max-scans N          play only the first N scans (default 0: all)
  --dir DIR              where links and sockets go (default /tmp/atlas-fakedev)
  --laser-link PATH      symlink to the laser's pty (default DIR/laser)
  --sonar-link PATH      symlink to the sonar's pty (default DIR/sonar)
  --can-socket PATH      the fake CAN bus socket (default DIR/can)
  --only DEVICE          run one device: laser, odometry or sonar
  --no-laser, --no-odometry, --no-sonar
  --lms-power-up-baud B  the scanner's rate at power-up: 9600, 19200, 38400 or 500000
                         (default 9600)
  --wait-for-drivers     start playing only when every device has its driver connected
                         (laser streaming, CAN client connected, P2OS opened)
  --progress-every S     print progress every S seconds, 0..1e6 (default 5; 0 = never)
fault injection (applied to --fault-device, default all):
  --fault-device D       laser, odometry, sonar or all
  (the *-every counts are integers 0..2147483647, 0 = never)
  --garbage-every N      garbage bytes before every Nth message
  --garbage-bytes N      how many, 1..4096 (default 40)
  --corrupt-every N      corrupt the CRC / checksum of every Nth message
  --truncate-every N     send only half of every Nth message
  --jump-every N         odometry counters jump every Nth 0x311 ...
  --jump-mm N            ... by N mm, a 32-bit integer (default 500000)
  --drop-after S --drop-for T   close the device after S s for T s, then recreate it
  --stall-after S --stall-for T send nothing from S s for T s
                         (S >= 0, T >= 0.001, at most 1e6 s; each pair goes together)
  --version              the version
  -h, --help             this text

Exits when the whole log has been played (or on SIGINT / SIGTERM).
example:
  atlas-fakedev --log ../shared/datasets/mit-csail/mit-csail.clf.gz --speed 10 \
      --dir /tmp/robot --wait-for-drivers
)";

std::atomic<bool> g_stop{false};
void OnSignal(int) { g_stop.store(true); }

int Fail(const std::string& msg) {
  std::fprintf(stderr, "atlas-fakedev: %s\n(see atlas-fakedev --help)\n", msg.c_str());
  return 2;
}

}  // namespace

int main(int argc, char** argv) {
  using namespace atlas;
  std::string log, dir = "/tmp/atlas-fakedev", laser_link, sonar_link, can_socket, only,
                   fault_device = "all";
  double speed = 1.0, progress_every = 5.0;
  int64_t max_scans = 0;
  int power_up_baud = 9600;
  bool drop_for_given = false, stall_for_given = false;
  bool laser = true, odometry = true, sonar = true, wait = false;
  fake::FaultOptions faults;
  for (int i = 1; i < argc; ++i) {
    const std::string a = argv[i];
    auto value = [&]() -> const char* { return i + 1 < argc ? argv[++i] : nullptr; };
    auto need = [&](const char* v) {
      if (v == nullptr) {
        std::fprintf(stderr, "atlas-fakedev: %s needs a value\n", a.c_str());
        std::exit(2);
      }
      return v;
    };
    std::string error;
    auto num = [&](double lo, double hi, double* out) {
      if (!NumberArgument(a, need(value()), lo, hi, *out, error)) std::exit(Fail(error));
    };
    auto integer = [&](int64_t lo, int64_t hi, auto* out) {
      if (!IntegerArgument(a, need(value()), lo, hi, *out, error)) std::exit(Fail(error));
    };
    constexpr int64_t kIntMax = std::numeric_limits<int>::max();
    constexpr double kLongest = 1e6;  // seconds, for the fault times and the progress period
    if (a == "--version") {
      std::fputs(atlas::VersionLine("atlas-fakedev").c_str(), stdout);
      return 0;
    }
    if (a == "-h" || a == "--help") {
      std::fputs(kHelp, stdout);
      return 0;
    } else if (a == "--log") {
      log = need(value());
    } else if (a == "--speed") {
      num(1e-3, 1000, &speed);
    } else if (a == "--max-scans") {
      integer(0, std::numeric_limits<int64_t>::max(), &max_scans);
    } else if (a == "--dir") {
      dir = need(value());
    } else if (a == "--laser-link") {
      laser_link = need(value());
    } else if (a == "--sonar-link") {
      sonar_link = need(value());
    } else if (a == "--can-socket") {
      can_socket = need(value());
    } else if (a == "--only") {
      only = need(value());
    } else if (a == "--no-laser") {
      laser = false;
    } else if (a == "--no-odometry") {
      odometry = false;
    } else if (a == "--no-sonar") {
      sonar = false;
    } else if (a == "--lms-power-up-baud") {
      integer(1, kIntMax, &power_up_baud);
    } else if (a == "--wait-for-drivers") {
      wait = true;
    } else if (a == "--progress-every") {
      num(0, kLongest, &progress_every);
    } else if (a == "--fault-device") {
      fault_device = need(value());
    } else if (a == "--garbage-every") {
      integer(0, kIntMax, &faults.garbage_every);
    } else if (a == "--garbage-bytes") {
      integer(1, 4096, &faults.garbage_bytes);
    } else if (a == "--corrupt-every") {
      integer(0, kIntMax, &faults.corrupt_crc_every);
    } else if (a == "--truncate-every") {
      integer(0, kIntMax, &faults.truncate_every);
    } else if (a == "--jump-every") {
      integer(0, kIntMax, &faults.jump_every);
    } else if (a == "--jump-mm") {
      integer(std::numeric_limits<int32_t>::min(), std::numeric_limits<int32_t>::max(),
              &faults.jump_mm);
    } else if (a == "--drop-after") {
      num(0, kLongest, &faults.drop_after_s);
    } else if (a == "--drop-for") {
      num(1e-3, kLongest, &faults.drop_for_s);
      drop_for_given = true;
    } else if (a == "--stall-after") {
      num(0, kLongest, &faults.stall_after_s);
    } else if (a == "--stall-for") {
      num(1e-3, kLongest, &faults.stall_for_s);
      stall_for_given = true;
    } else {
      return Fail("unknown option " + a);
    }
  }
  if (log.empty()) return Fail("--log FILE is required");
  if (drop_for_given != (faults.drop_after_s >= 0))
    return Fail("--drop-after S and --drop-for T go together");
  if (stall_for_given != (faults.stall_after_s >= 0))
    return Fail("--stall-after S and --stall-for T go together");
  if (!only.empty()) {
    if (only != "laser" && only != "odometry" && only != "sonar")
      return Fail("--only must be laser, odometry or sonar, not " + only);
    laser = only == "laser";
    odometry = only == "odometry";
    sonar = only == "sonar";
  }
  if (!laser && !odometry && !sonar) return Fail("no device left to run");
  if (fault_device != "all" && fault_device != "laser" && fault_device != "odometry" &&
      fault_device != "sonar")
    return Fail("--fault-device must be laser, odometry, sonar or all");
  if (std::string e = faults.Validate(); !e.empty()) return Fail(e);
  auto faults_for = [&](const char* device) {
    return (fault_device == "all" || fault_device == device) ? faults : fake::FaultOptions{};
  };
  if (mkdir(dir.c_str(), 0755) != 0 && errno != EEXIST)
    return Fail("cannot create " + dir + ": " + std::strerror(errno));
  if (laser_link.empty()) laser_link = dir + "/laser";
  if (sonar_link.empty()) sonar_link = dir + "/sonar";
  if (can_socket.empty()) can_socket = dir + "/can";

  std::printf("reading %s ...\n", log.c_str());
  std::fflush(stdout);
  auto rec = std::make_shared<fake::Recording>();
  std::string error;
  if (!fake::LoadCarmenRecording(log, static_cast<size_t>(max_scans), rec.get(), &error))
    return Fail("cannot play the log: " + error);
  const double length_s = ToSeconds(rec->end - rec->begin);
  std::printf("%zu scans, %zu odometry poses, %.1f s of log; at %.3gx: %.1f s\n", rec->scans.size(),
              rec->odometry.size(), length_s, speed, length_s / speed);

  auto clock = std::make_shared<fake::PlaybackClock>(rec->begin, speed);
  std::unique_ptr<fake::FakeLms> lms;
  std::unique_ptr<fake::FakeAgilexBase> base;
  std::unique_ptr<fake::FakeP2os> p2os;
  if (laser) {
    fake::FakeLmsOptions o;
    o.link = laser_link;
    o.power_up_baud = power_up_baud;
    o.faults = faults_for("laser");
    o.sent_record_capacity = 0;  // only the totals are reported
    if (std::string e = o.Validate(); !e.empty()) return Fail(e);
    lms = std::make_unique<fake::FakeLms>(o, rec, clock);
    if (!lms->Open(&error)) return Fail(error);
    std::printf("laser:    %s (LMS 2xx, powers up at %d baud)\n", lms->path().c_str(),
                power_up_baud);
  }
  if (odometry) {
    fake::FakeAgilexOptions o;
    o.socket_path = can_socket;
    o.faults = faults_for("odometry");
    o.sent_record_capacity = 0;  // only the totals are reported
    if (std::string e = o.Validate(); !e.empty()) return Fail(e);
    base = std::make_unique<fake::FakeAgilexBase>(o, rec, clock);
    if (!base->Open(&error)) return Fail(error);
    std::printf("odometry: %s (AgileX CAN, fake bus)\n", base->interface_name().c_str());
  }
  if (sonar) {
    fake::FakeP2osOptions o;
    o.link = sonar_link;
    o.faults = faults_for("sonar");
    o.sent_record_capacity = 0;  // only the totals are reported
    if (std::string e = o.Validate(); !e.empty()) return Fail(e);
    p2os = std::make_unique<fake::FakeP2os>(o, rec, clock);
    if (!p2os->Open(&error)) return Fail(error);
    std::printf("sonar:    %s (P2OS, 9600 baud)\n", p2os->path().c_str());
  }
  std::fflush(stdout);
  signal(SIGINT, OnSignal);
  signal(SIGTERM, OnSignal);
  signal(SIGPIPE, SIG_IGN);
  if (lms) lms->Start();
  if (base) base->Start();
  if (p2os) p2os->Start();

  if (wait) {
    std::printf("waiting for the drivers ...\n");
    std::fflush(stdout);
    while (!g_stop.load()) {
      if ((!lms || lms->streaming()) && (!base || base->clients() > 0) &&
          (!p2os || p2os->is_open()))
        break;
      std::this_thread::sleep_for(std::chrono::milliseconds(5));
    }
  }
  clock->Start();
  // The mapping from this machine's monotonic clock (the stamps drivers give the data) back to
  // log time: log = log_start + (monotonic - monotonic_start) * speed.
  std::printf("playing: log_start %.6f monotonic_start %.6f speed %.9g\n",
              ToSeconds(clock->log_start()), ToSeconds(clock->WallAt(clock->log_start())), speed);
  std::fflush(stdout);
  const Time start = Now();
  Time next_progress = start + FromSeconds(progress_every).time_since_epoch();
  auto finished = [&] {
    return (!lms || lms->finished()) && (!base || base->finished()) && (!p2os || p2os->finished());
  };
  auto report = [&](const char* what) {
    std::printf("%s %.1f s:", what, ToSeconds(Now() - start));
    if (lms) {
      const auto& f = lms->fault_counts();
      std::printf(
          " laser %llu scans intact / %llu sent (garbage %llu corrupt %llu trunc %llu "
          "drops %llu stalls %llu);",
          (unsigned long long)lms->sent_intact().total(), (unsigned long long)lms->messages_sent(),
          (unsigned long long)f.garbage, (unsigned long long)f.corrupted,
          (unsigned long long)f.truncated, (unsigned long long)f.drops,
          (unsigned long long)f.stalls);
    }
    if (base) {
      const auto& f = base->fault_counts();
      std::printf(" odometry %llu 0x311 intact, %llu frames (jumps %llu drops %llu);",
                  (unsigned long long)base->sent_intact().total(),
                  (unsigned long long)base->frames_sent(), (unsigned long long)f.jumps,
                  (unsigned long long)f.drops);
    }
    if (p2os)
      std::printf(" sonar %llu SIPs with returns, %llu pulses",
                  (unsigned long long)p2os->sent_intact().total(),
                  (unsigned long long)p2os->pulse_times().total());
    std::printf("\n");
    std::fflush(stdout);
  };
  while (!g_stop.load() && !finished()) {
    std::this_thread::sleep_for(std::chrono::milliseconds(20));
    if (progress_every > 0 && Now() >= next_progress) {
      report("progress");
      next_progress += FromSeconds(progress_every).time_since_epoch();
    }
  }
  // Give the drivers a moment to read the last bytes before the devices vanish.
  std::this_thread::sleep_for(std::chrono::milliseconds(200));
  report(g_stop.load() ? "stopped" : "done");
  if (lms) lms->Stop();
  if (base) base->Stop();
  if (p2os) p2os->Stop();
  return 0;
}
