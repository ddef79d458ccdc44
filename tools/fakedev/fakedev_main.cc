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
#include <optional>
#include <string>
#include <thread>

#include "drivers/fake/fake_agilex_base.h"
#include "drivers/fake/fake_lms.h"
#include "drivers/fake/fake_p2os.h"
#include "drivers/fake/playback.h"
#include "tools/cli/command_line.h"

namespace {

constexpr const char* kDescription =
    R"(Fake robot devices for atlasd, playing a CARMEN log (plain or .gz) as real device bytes:
  laser     a SICK LMS 2xx on a pseudo-terminal (answers status, mode, variant and the baud
            switch; streams 0xB0 telegrams in continuous mode)
  odometry  an AgileX base on the fake CAN bus: a Unix SOCK_SEQPACKET socket, one struct
            can_frame per datagram (0x311 and 0x221 every 20 ms, 0x211 every 100 ms);
            point atlasd at  unix:PATH
  sonar     a Pioneer P2OS controller on a pseudo-terminal (SYNC handshake, OPEN, sonar on,
            SIPs every 100 ms with returns synthesised from the laser)
Run all devices in one process (default) or one per process (--only laser|odometry|sonar).)";

constexpr const char* kFooter =
    R"(Exits when the whole log has been played (or on SIGINT / SIGTERM).
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
  constexpr int64_t kIntMax = std::numeric_limits<int>::max();
  constexpr double kLongest = 1e6;  // seconds, for the fault times and the progress period
  cli::CommandLine command_line("atlas-fakedev", {"atlas-fakedev --log FILE [options]"},
                                kDescription, kFooter);
  CLI::App& app = command_line.app();
  cli::AddText(app, "--log", "FILE", &log, "the CARMEN log to play (required)");
  cli::AddNumber(app, "--speed", "F", 1e-3, 1000, &speed,
                 "playback speed, 1 = real time, 0.001..1000 (default 1)");
  cli::AddInteger(app, "--max-scans", "N", 0, std::numeric_limits<int64_t>::max(), &max_scans,
                  "play only the first N scans (default 0: all)");
  cli::AddText(app, "--dir", "DIR", &dir,
               "where links and sockets go (default /tmp/atlas-fakedev)");
  cli::AddText(app, "--laser-link", "PATH", &laser_link,
               "symlink to the laser's pty (default DIR/laser)");
  cli::AddText(app, "--sonar-link", "PATH", &sonar_link,
               "symlink to the sonar's pty (default DIR/sonar)");
  cli::AddText(app, "--can-socket", "PATH", &can_socket,
               "the fake CAN bus socket (default DIR/can)");
  cli::AddChoice(app, "--only", "DEVICE", {"laser", "odometry", "sonar"}, &only,
                 "run one device: laser, odometry or sonar");
  bool no_laser = false, no_odometry = false, no_sonar = false;
  cli::AddFlag(app, "--no-laser", &no_laser, "no laser");
  cli::AddFlag(app, "--no-odometry", &no_odometry, "no odometry");
  cli::AddFlag(app, "--no-sonar", &no_sonar, "no sonar");
  cli::AddInteger(app, "--lms-power-up-baud", "B", 1, kIntMax, &power_up_baud,
                  "the scanner's rate at power-up: 9600, 19200, 38400 or 500000\n"
                  "(default 9600)");
  cli::AddFlag(app, "--wait-for-drivers", &wait,
               "start playing only when every device has its driver connected\n"
               "(laser streaming, CAN client connected, P2OS opened)");
  cli::AddNumber(app, "--progress-every", "S", 0, kLongest, &progress_every,
                 "print progress every S seconds, 0..1e6 (default 5; 0 = never)");
  // Applied to --fault-device (default all); the *-every counts are 0 = never.
  const std::string faults_group = "Fault injection";
  cli::AddChoice(app, "--fault-device", "D", {"laser", "odometry", "sonar", "all"}, &fault_device,
                 "laser, odometry, sonar or all: where the faults below go (default all);\n"
                 "the *-every counts are integers 0..2147483647, 0 = never")
      .Group(faults_group);
  cli::AddInteger(app, "--garbage-every", "N", 0, kIntMax, &faults.garbage_every,
                  "garbage bytes before every Nth message")
      .Group(faults_group);
  cli::AddInteger(app, "--garbage-bytes", "N", 1, 4096, &faults.garbage_bytes,
                  "how many, 1..4096 (default 40)")
      .Group(faults_group);
  cli::AddInteger(app, "--corrupt-every", "N", 0, kIntMax, &faults.corrupt_crc_every,
                  "corrupt the CRC / checksum of every Nth message")
      .Group(faults_group);
  cli::AddInteger(app, "--truncate-every", "N", 0, kIntMax, &faults.truncate_every,
                  "send only half of every Nth message")
      .Group(faults_group);
  cli::AddInteger(app, "--jump-every", "N", 0, kIntMax, &faults.jump_every,
                  "odometry counters jump every Nth 0x311 ...")
      .Group(faults_group);
  cli::AddInteger(app, "--jump-mm", "N", std::numeric_limits<int32_t>::min(),
                  std::numeric_limits<int32_t>::max(), &faults.jump_mm,
                  "... by N mm, a 32-bit integer (default 500000)")
      .Group(faults_group);
  cli::AddNumber(app, "--drop-after", "S", 0, kLongest, &faults.drop_after_s,
                 "close the device after S s ...")
      .Group(faults_group);
  cli::AddNumber(app, "--drop-for", "T", 1e-3, kLongest, &faults.drop_for_s,
                 "... for T s, then recreate it (the two go together)")
      .Group(faults_group)
      .Each([&](const std::string&) { drop_for_given = true; });
  cli::AddNumber(app, "--stall-after", "S", 0, kLongest, &faults.stall_after_s,
                 "send nothing from S s ...")
      .Group(faults_group);
  cli::AddNumber(app, "--stall-for", "T", 1e-3, kLongest, &faults.stall_for_s,
                 "... for T s (the two go together)")
      .Group(faults_group)
      .Each([&](const std::string&) { stall_for_given = true; });
  if (std::optional<int> done = command_line.Parse(argc, argv)) return *done;
  if (no_laser) laser = false;
  if (no_odometry) odometry = false;
  if (no_sonar) sonar = false;
  auto Usage = [&](const std::string& what) { return command_line.Usage(what); };
  if (log.empty()) return Usage("--log FILE is required");
  if (drop_for_given != (faults.drop_after_s >= 0))
    return Usage("--drop-after S and --drop-for T go together");
  if (stall_for_given != (faults.stall_after_s >= 0))
    return Usage("--stall-after S and --stall-for T go together");
  if (!only.empty()) {
    laser = only == "laser";
    odometry = only == "odometry";
    sonar = only == "sonar";
  }
  if (!laser && !odometry && !sonar) return Usage("no device left to run");
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
