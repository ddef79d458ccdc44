// Latency of atlasd's whole live path in one process, with the real parts (docs/atlasd.md,
// "Measurements"): from the last byte of a SICK LMS telegram written on a pseudo-terminal to the
// ATLAS_POSE it produced, received by an LCM subscriber over UDP multicast.
//
//   pty (termios) -> LaserReader thread -> SpscQueue -> the live daemon's loop thread (StepLoop,
//   Atlas::Localize) -> AtlasPublisher (LCM udpm) -> an lcm::LCM subscriber thread
//
// The daemon is RunLiveDaemon() itself (live_daemon.h: readers, queues, loop, store writer,
// signals) on the shipped config/atlasd.toml, with only the device paths, the simulated laser's
// unit and range, the LCM URL, the state directory and [scheduling] changed. The scans and the
// odometry come from a simulated run through a generated building (sim; 181 beams at
// 75 Hz, odometry at 50 Hz): the fake AgileX base plays the odometry on the fake CAN bus at real
// time (drivers/fake), and the benchmark writes each scan's 0xB0 telegram (sick::
// EncodeMeasuredValues, the bytes the fake LMS sends) in one write() at its real time on the
// same playback clock, open loop as a scanner does, whether or not the previous pose came back.
//
// Each iteration is one scan: the time is stamped just before the write() (so the figure
// includes the write call: an upper bound on "from the last byte written"), and the iteration
// sleeps until the next scan is due. The receipts (pose_t.utime = the reader's arrival stamp of
// the scan, published as microseconds since the epoch and turned back into CLOCK_MONOTONIC with
// an EpochClock read here; and the subscriber's CLOCK_MONOTONIC time in its handler) are matched
// to the writes
// afterwards: the pose of scan k has the largest k whose write began before its arrival stamp;
// poses are in scan order, so when two poses give the same k (the reader was late and read two
// telegrams at once) the earlier pose is the earlier scan. Counters: median, p90, p99 and max
// of (receipt - write) in microseconds over the timed scans, and the p99 and max of its two hops
// (to_arrival: write -> the reader's arrival stamp; from_arrival: arrival stamp -> receipt);
// `missing` scans without a pose (dropped by the loop or lost); overruns and dropped scans from the
// daemon's last ATLAS_HEALTH; the 1-minute load average at the start and the end. The manual
// iteration time is the pose's latency when it came before the next scan was due (else the time
// until then).
//
// LCM multicast is sent only inside a private network namespace: the benchmark refuses to run
// unless LCM_DEFAULT_URL is udpm:// and lo is the only network interface (memq:// cannot serve:
// the subscriber is its own LCM instance, as a real consumer would be). Run it with
//   scripts/atlasd-latency-benchmark.sh [benchmark flags]
// which makes the namespace. ATLAS_LATENCY_SECONDS (default 60) sets the timed length of each run.
//
// Arguments: fifo = SCHED_FIFO priority of the loop and reader threads (0: policy "other");
// sub_fifo = the subscriber thread's (0: normal); pin = 0 spread (no affinity), 1 the loop
// thread on CPU 1 by scheduling.cpu_affinity (the config key), 2 all of atlasd's threads
// (started from a thread bound to CPU 1, as `taskset -c 1` or systemd's CPUAffinity=1 would) and
// the subscriber on CPU 1, 3 atlasd's threads on CPU 1 and the subscriber on CPU 0. The threads
// standing in for the devices (this writer, the fake base) are not pinned; the writer runs
// SCHED_FIFO 45 (above atlasd) where allowed, counter writer_fifo, so that the telegrams go out
// on time (late_writes: writes more than 1 ms after their time).
#include <benchmark/benchmark.h>
#include <net/if.h>
#include <pthread.h>
#include <sched.h>
#include <signal.h>
#include <stdlib.h>
#include <time.h>
#include <unistd.h>

#include <algorithm>
#include <atomic>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <lcm/lcm-cpp.hpp>
#include <memory>
#include <mutex>
#include <string>
#include <thread>
#include <vector>

#include "atlasd/health_t.hpp"
#include "atlasd/pose_t.hpp"
#include "atlas_paths.h"
#include "daemon/atlasd/daemon_setup.h"
#include "daemon/atlasd/live_daemon.h"
#include "daemon/lcm_out/epoch_clock.h"
#include "drivers/fake/fake_agilex_base.h"
#include "drivers/fake/fake_lms.h"
#include "drivers/fake/playback.h"
#include "drivers/serial/pseudo_terminal.h"
#include "drivers/sick/lms_messages.h"
#include "formats/config/config_loader.h"
#include "sim/building_generator.h"
#include "sim/simulation.h"

namespace atlas {
namespace {

constexpr double kLaserHz = 75.0;
constexpr size_t kWarmupScans = 150;  // 2 s: start-up, first frames
constexpr int kDaemonCpu = 1;
constexpr int kOtherCpu = 0;
constexpr int kWriterPriority = 45;  // the telegram writer, above atlasd's threads

int TimedSeconds() {
  const char* s = std::getenv("ATLAS_LATENCY_SECONDS");
  const int v = s ? std::atoi(s) : 60;
  return v > 0 ? v : 60;
}
int64_t ScansPerRun() { return static_cast<int64_t>(TimedSeconds() * kLaserHz); }

// Empty when LCM multicast may be sent here, else why not and what to do.
std::string WhyNoPrivateMulticast(const std::string& url) {
  const std::string run = "; run scripts/atlasd-latency-benchmark.sh, which makes one (unshare -n)";
  if (url.rfind("udpm://", 0) != 0)
    return "LCM_DEFAULT_URL is '" + url +
           "': the benchmark needs udpm:// in a private network namespace (memq:// cannot reach "
           "a subscriber in another LCM instance)" +
           run;
  std::string others;
  if (struct if_nameindex* names = if_nameindex()) {
    for (struct if_nameindex* n = names; n->if_index != 0; ++n)
      if (std::string(n->if_name) != "lo") others += std::string(" ") + n->if_name;
    if_freenameindex(names);
  }
  if (!others.empty())
    return "network interfaces besides lo:" + others +
           ": LCM multicast is sent only inside a private network namespace" + run;
  return "";
}

double LoadAverage() {
  std::ifstream in("/proc/loadavg");
  double v = -1;
  in >> v;
  return v;
}

// Binds the calling thread to `cpu` (-1: leaves it) and gives it SCHED_FIFO `priority` (0:
// leaves it). Empty on success, else what was refused.
std::string ScheduleThisThread(int priority, int cpu) {
  std::string why;
  if (cpu >= 0) {
    cpu_set_t set;
    CPU_ZERO(&set);
    CPU_SET(cpu, &set);
    if (pthread_setaffinity_np(pthread_self(), sizeof(set), &set) != 0)
      why += "CPU affinity refused; ";
  }
  if (priority > 0) {
    sched_param p{};
    p.sched_priority = priority;
    if (pthread_setschedparam(pthread_self(), SCHED_FIFO, &p) != 0) why += "SCHED_FIFO refused; ";
  }
  return why;
}

class RecordingSink final : public sim::SimulationSink {
 public:
  explicit RecordingSink(fake::Recording* r) : r_(r) {}
  void OnTruth(const TruthSample&) override {}
  void OnOdometry(const OdometrySample& o, double, double) override { r_->odometry.push_back(o); }
  void OnLaser(const LaserScan& s, const Pose2&) override { r_->scans.push_back(s); }
  void OnSonar(const SonarReading&, const Pose2&) override {}

 private:
  fake::Recording* r_;
};

// A run through a generated building long enough for `seconds`, made once per process.
std::shared_ptr<const fake::Recording> SimulatedRun(double seconds, const Pose2& laser_mount,
                                                    std::string* error) {
  static std::shared_ptr<fake::Recording> cached;
  if (cached && ToSeconds(cached->end - cached->begin) >= seconds) return cached;
  sim::SimulationOptions o;
  o.odometry_hz = 50.0;
  o.start_time = 1000.0;
  o.laser_options.beams = 181;
  o.laser_options.rate_hz = kLaserHz;
  o.laser_options.mount = laser_mount;
  o.seed = 3;
  o.length_m = seconds * o.motion_options.max_speed + 5.0;  // never faster than max_speed
  sim::BuildingOptions b;
  const sim::World world = sim::GenerateBuilding(b, o.seed);
  auto rec = std::make_shared<fake::Recording>();
  RecordingSink sink(rec.get());
  const sim::SimulationSummary s = sim::Simulate(world, o, sink);
  if (!s.error.empty() || rec->scans.empty() || rec->odometry.empty()) {
    *error = "simulation failed: " + s.error;
    return nullptr;
  }
  rec->begin = std::min(rec->scans.front().stamp, rec->odometry.front().stamp);
  rec->end = std::max(rec->scans.back().stamp, rec->odometry.back().stamp);
  cached = rec;
  return rec;
}

struct Receipt {
  int64_t utime = 0;  // the scan's arrival stamp: pose_t.utime back on the monotonic clock
  Time received{};
};

// The consumer of the pose: its own LCM instance and thread, as another process would have.
class PoseSubscriber {
 public:
  PoseSubscriber(const std::string& url, const LcmChannels& channels, size_t capacity)
      : lcm_(url), receipts_(capacity) {
    lcm_.subscribe(channels.pose, &PoseSubscriber::OnPose, this);
    lcm_.subscribe(channels.health, &PoseSubscriber::OnHealth, this);
  }
  ~PoseSubscriber() { Stop(); }
  bool good() { return lcm_.good(); }
  void Start(int priority, int cpu) {
    thread_ = std::thread([this, priority, cpu] {
      schedule_error_ = ScheduleThisThread(priority, cpu);
      while (!stop_.load(std::memory_order_relaxed)) lcm_.handleTimeout(50);
    });
  }
  void Stop() {
    stop_.store(true);
    if (thread_.joinable()) thread_.join();
  }
  size_t count() const { return count_.load(std::memory_order_acquire); }
  const Receipt& at(size_t i) const { return receipts_[i]; }
  atlasd::health_t LastHealth() {
    std::lock_guard<std::mutex> lock(health_mutex_);
    return health_;
  }
  const std::string& schedule_error() const { return schedule_error_; }

 private:
  void OnPose(const lcm::ReceiveBuffer*, const std::string&, const atlasd::pose_t* p) {
    const Time now = Now();
    const size_t n = count_.load(std::memory_order_relaxed);
    if (n == receipts_.size()) return;
    receipts_[n] = Receipt{epoch_.ToMonotonic(p->utime), now};
    count_.store(n + 1, std::memory_order_release);
  }
  void OnHealth(const lcm::ReceiveBuffer*, const std::string&, const atlasd::health_t* h) {
    std::lock_guard<std::mutex> lock(health_mutex_);
    health_ = *h;
  }

  lcm::LCM lcm_;
  const EpochClock epoch_ = EpochClock::Capture();  // as the daemon's, read in this process
  std::vector<Receipt> receipts_;
  std::atomic<size_t> count_{0};
  std::mutex health_mutex_;
  atlasd::health_t health_{};
  std::thread thread_;
  std::atomic<bool> stop_{false};
  std::string schedule_error_;
};

// RunLiveDaemon on its own thread; Stop() sends it SIGTERM, as systemd would.
class DaemonThread {
 public:
  void Start(const DaemonOptions& options, int cpu) {
    thread_ = std::thread([this, options, cpu] {
      // Blocked before anything else, so that the SIGTERM meant for RunLiveDaemon's
      // sigtimedwait can never kill the process.
      sigset_t signals;
      sigemptyset(&signals);
      for (int s : {SIGTERM, SIGINT, SIGHUP, SIGUSR1}) sigaddset(&signals, s);
      pthread_sigmask(SIG_BLOCK, &signals, nullptr);
      ScheduleThisThread(0, cpu);  // inherited by every thread atlasd starts
      LiveFlags flags;
      flags.quiet = true;
      exit_code_.store(RunLiveDaemon(options, flags));
      done_.store(true);
    });
  }
  // Returns atlasd's exit code.
  int Stop() {
    if (!thread_.joinable()) return -1;
    if (!done_.load()) pthread_kill(thread_.native_handle(), SIGTERM);
    thread_.join();
    return exit_code_.load();
  }
  bool done() const { return done_.load(); }
  ~DaemonThread() { Stop(); }

 private:
  std::thread thread_;
  std::atomic<int> exit_code_{-1};
  std::atomic<bool> done_{false};
};

void SleepUntil(Time t) {
  const int64_t ns = t.time_since_epoch().count();
  timespec ts{static_cast<time_t>(ns / 1000000000), static_cast<long>(ns % 1000000000)};
  while (clock_nanosleep(CLOCK_MONOTONIC, TIMER_ABSTIME, &ts, nullptr) == EINTR) {
  }
}

double Quantile(const std::vector<double>& sorted, double q) {
  if (sorted.empty()) return 0.0;
  return sorted[std::min(sorted.size() - 1,
                         static_cast<size_t>(q * static_cast<double>(sorted.size())))];
}

// For each receipt, the index of the scan whose pose it is (-1: before the first write).
std::vector<int64_t> MatchReceiptsToWrites(const std::vector<Receipt>& receipts,
                                           const std::vector<Time>& written) {
  std::vector<int64_t> scan(receipts.size(), -1);
  int64_t next = static_cast<int64_t>(written.size());
  for (size_t j = receipts.size(); j-- > 0;) {
    // utime is whole microseconds: the arrival was before utime + 1 us.
    const Time arrival_bound = Time(Duration(receipts[j].utime * 1000 + 999));
    const int64_t k =
        (std::upper_bound(written.begin(), written.end(), arrival_bound) - written.begin()) - 1;
    scan[j] = std::min(k, next - 1);
    if (scan[j] >= 0) next = scan[j];
  }
  return scan;
}

void BM_TelegramToPoseReceived(benchmark::State& state) {
  const int fifo = static_cast<int>(state.range(0));
  const int sub_fifo = static_cast<int>(state.range(1));
  const int pin = static_cast<int>(state.range(2));
  const char* env_url = std::getenv("LCM_DEFAULT_URL");
  const std::string url = env_url ? env_url : "";
  if (std::string why = WhyNoPrivateMulticast(url); !why.empty()) {
    state.SkipWithError(why.c_str());
    return;
  }
  const std::string config_path = std::string(ATLAS_SOURCE_DIR) + "/config/atlasd.toml";
  ConfigResult config = LoadConfigFile(config_path, ValidateDerivedOptions);
  if (!config.ok()) {
    state.SkipWithError((config_path + ": " + config.errors.front().ToString()).c_str());
    return;
  }
  DaemonOptions o = config.options;
  const Pose2 mount{o.laser.mount.x_m, o.laser.mount.y_m, o.laser.mount.theta_deg * M_PI / 180.0};
  std::string error;
  const double run_s = static_cast<double>(kWarmupScans + state.max_iterations) / kLaserHz + 5.0;
  std::shared_ptr<const fake::Recording> rec = SimulatedRun(run_s, mount, &error);
  if (!rec || rec->scans.size() < kWarmupScans + static_cast<size_t>(state.max_iterations) + 1) {
    state.SkipWithError(("the simulated run is too short: " + error).c_str());
    return;
  }
  std::vector<std::vector<uint8_t>> telegrams;
  telegrams.reserve(rec->scans.size());
  for (const LaserScan& s : rec->scans)
    telegrams.push_back(*sick::EncodeMeasuredValues(s, sick::Unit::kCentimetre, 0x10));

  char dir_template[] = "/tmp/atlasd-latency-XXXXXX";
  if (!mkdtemp(dir_template)) {
    state.SkipWithError("mkdtemp failed");
    return;
  }
  const std::string dir = dir_template;
  PseudoTerminal pty;
  auto clock = std::make_shared<fake::PlaybackClock>(rec->begin, 1.0);
  fake::FakeAgilexOptions base_options;
  base_options.socket_path = dir + "/can";
  base_options.track_width_m = o.odometry.track_width_m;
  fake::FakeAgilexBase base(base_options, rec, clock);
  if (!pty.Create(dir + "/laser", &error) || !base.Open(&error)) {
    state.SkipWithError(error.c_str());
    return;
  }
  base.Start();

  o.laser.device = dir + "/laser";
  o.laser.unit = sick::Unit::kCentimetre;  // the simulated laser reaches 30 m (80 m mode)
  o.laser.max_range_m = 30.0;
  o.odometry.interface = base.interface_name();
  o.sonar.enabled = false;
  o.lcm.url = url;
  o.state.directory = dir + "/state";
  o.scheduling.policy = fifo > 0 ? SchedPolicy::kFifo : SchedPolicy::kOther;
  o.scheduling.priority = fifo;
  o.scheduling.cpu_affinity.clear();
  if (pin >= 1) o.scheduling.cpu_affinity = {kDaemonCpu};
  const int daemon_cpu = pin >= 2 ? kDaemonCpu : -1;
  const int subscriber_cpu = pin == 2 ? kDaemonCpu : pin == 3 ? kOtherCpu : -1;

  const size_t total_scans = kWarmupScans + static_cast<size_t>(state.max_iterations);
  PoseSubscriber subscriber(url, o.lcm.channels, total_scans + 4096);
  if (!subscriber.good()) {
    state.SkipWithError(("cannot open LCM at " + url + " (is there a multicast route?)").c_str());
    return;
  }
  subscriber.Start(sub_fifo, subscriber_cpu);
  DaemonThread daemon;
  daemon.Start(o, daemon_cpu);
  const bool streaming = fake::AnswerLmsStartUp(pty, std::chrono::seconds(10));
  const Time connect_deadline = Now() + std::chrono::seconds(5);
  while (base.clients() == 0 && Now() < connect_deadline)
    std::this_thread::sleep_for(std::chrono::milliseconds(5));
  if (!streaming || base.clients() == 0 || daemon.done()) {
    state.SkipWithError("atlasd did not start the laser or connect to the CAN bus (see stderr)");
    return;
  }
  // This thread stands in for the scanner, which does not share the robot's CPUs: it runs above
  // atlasd's real-time threads, so that the telegrams go out at their times (where allowed).
  const bool writer_fifo = ScheduleThisThread(kWriterPriority, -1).empty();
  const double load_start = LoadAverage();
  clock->Start();

  std::vector<Time> written;
  written.reserve(total_scans);
  int late_writes = 0;
  // Sleeps until scan i is due, writes its telegram; the stamp is taken before write().
  auto write_scan = [&](size_t i) {
    const Time due = clock->WallAt(rec->scans[i].stamp);
    SleepUntil(due);
    const Time w = Now();
    if (w - due > std::chrono::milliseconds(1)) ++late_writes;
    written.push_back(w);
    pty.WriteAll(telegrams[i].data(), telegrams[i].size());
  };
  for (size_t i = 0; i < kWarmupScans; ++i) write_scan(i);
  const int late_in_warmup = late_writes;
  size_t seen = 0;
  for (auto _ : state) {
    const size_t i = written.size();
    write_scan(i);
    const Time w = written.back();
    SleepUntil(clock->WallAt(rec->scans[i + 1].stamp));
    double latency_s = ToSeconds(Now() - w);  // no pose yet: at least this
    for (; seen < subscriber.count(); ++seen) {
      const Receipt& r = subscriber.at(seen);
      if (r.utime * 1000 + 999 >= w.time_since_epoch().count()) {
        latency_s = ToSeconds(r.received - w);
        ++seen;
        break;
      }
    }
    state.SetIterationTime(latency_s);
  }
  if (writer_fifo) {
    sched_param normal{};
    pthread_setschedparam(pthread_self(), SCHED_OTHER, &normal);
  }
  std::this_thread::sleep_for(std::chrono::milliseconds(300));  // the last poses
  const double load_end = LoadAverage();
  const atlasd::health_t health = subscriber.LastHealth();
  const int exit_code = daemon.Stop();
  subscriber.Stop();
  base.Stop();
  std::error_code ec;
  std::filesystem::remove_all(dir, ec);

  std::vector<Receipt> receipts(subscriber.count());
  for (size_t j = 0; j < receipts.size(); ++j) receipts[j] = subscriber.at(j);
  const std::vector<int64_t> scan = MatchReceiptsToWrites(receipts, written);
  // The whole path, and its two hops: write -> the reader's arrival stamp, arrival -> receipt.
  std::vector<double> latency_us, to_arrival_us, from_arrival_us;
  for (size_t j = 0; j < receipts.size(); ++j) {
    if (scan[j] < static_cast<int64_t>(kWarmupScans)) continue;
    const Time arrival = Time(Duration(receipts[j].utime * 1000));
    latency_us.push_back(ToSeconds(receipts[j].received - written[scan[j]]) * 1e6);
    to_arrival_us.push_back(ToSeconds(arrival - written[scan[j]]) * 1e6);
    from_arrival_us.push_back(ToSeconds(receipts[j].received - arrival) * 1e6);
  }
  for (auto* v : {&latency_us, &to_arrival_us, &from_arrival_us}) std::sort(v->begin(), v->end());
  const size_t timed = written.size() - kWarmupScans;
  state.counters["median_us"] = Quantile(latency_us, 0.5);
  state.counters["p90_us"] = Quantile(latency_us, 0.9);
  state.counters["p99_us"] = Quantile(latency_us, 0.99);
  state.counters["max_us"] = latency_us.empty() ? 0.0 : latency_us.back();
  state.counters["to_arrival_p99_us"] = Quantile(to_arrival_us, 0.99);
  state.counters["to_arrival_max_us"] = to_arrival_us.empty() ? 0.0 : to_arrival_us.back();
  state.counters["from_arrival_p99_us"] = Quantile(from_arrival_us, 0.99);
  state.counters["from_arrival_max_us"] = from_arrival_us.empty() ? 0.0 : from_arrival_us.back();
  state.counters["poses"] = static_cast<double>(latency_us.size());
  state.counters["missing"] = static_cast<double>(timed - latency_us.size());
  state.counters["late_writes"] = late_writes - late_in_warmup;
  state.counters["writer_fifo"] = writer_fifo ? kWriterPriority : 0;
  state.counters["overruns"] = static_cast<double>(health.overruns);
  state.counters["dropped"] = static_cast<double>(health.dropped_scans);
  state.counters["load_start"] = load_start;
  state.counters["load_end"] = load_end;
  if (exit_code != 0) state.SkipWithError("atlasd exited non-zero (see stderr)");
  if (!subscriber.schedule_error().empty())
    state.SetLabel("subscriber: " + subscriber.schedule_error());
}
// The machine's floor, without atlasd: how late a thread like atlasd's wakes here. A thread on
// `cpu` at SCHED_FIFO 40 sleeps to absolute deadlines 1 ms apart (as cyclictest does); each
// iteration is one wake-up, its time the lateness. Counters: median, p99, max lateness, and
// gaps_over_2ms. A late wake-up of a real-time thread on an otherwise busy CPU means the
// virtual CPU itself was not running (the hypervisor), which no setting inside atlasd changes.
void BM_RealTimeWakeUpLateness(benchmark::State& state) {
  const int cpu = static_cast<int>(state.range(0));
  std::vector<double> late_us;
  late_us.reserve(static_cast<size_t>(state.max_iterations));
  const double load_start = LoadAverage();
  std::thread sleeper([&] {
    const bool fifo = ScheduleThisThread(40, cpu).empty();
    Time next = Now();
    for (auto _ : state) {
      next += std::chrono::milliseconds(1);
      SleepUntil(next);
      const double late = ToSeconds(Now() - next);
      late_us.push_back(late * 1e6);
      state.SetIterationTime(late);
    }
    if (!fifo) state.SetLabel("SCHED_FIFO refused");
  });
  sleeper.join();
  std::sort(late_us.begin(), late_us.end());
  state.counters["median_us"] = Quantile(late_us, 0.5);
  state.counters["p99_us"] = Quantile(late_us, 0.99);
  state.counters["max_us"] = late_us.empty() ? 0.0 : late_us.back();
  state.counters["gaps_over_2ms"] =
      static_cast<double>(late_us.end() - std::upper_bound(late_us.begin(), late_us.end(), 2000.0));
  state.counters["load_start"] = load_start;
  state.counters["load_end"] = LoadAverage();
}
BENCHMARK(BM_RealTimeWakeUpLateness)
    ->ArgName("cpu")
    ->Arg(0)
    ->Arg(1)
    ->Iterations(30000)
    ->UseManualTime()
    ->Unit(benchmark::kMicrosecond);

BENCHMARK(BM_TelegramToPoseReceived)
    ->ArgNames({"fifo", "sub_fifo", "pin"})
    ->Args({40, 0, 0})   // the shipped [scheduling], subscriber at normal priority
    ->Args({40, 40, 0})  // everything SCHED_FIFO 40, spread over the CPUs
    ->Args({40, 40, 1})  // ... the loop thread on CPU 1 (scheduling.cpu_affinity = [1])
    ->Args({40, 40, 2})  // ... atlasd and the subscriber on CPU 1
    ->Args({40, 40, 3})  // ... atlasd on CPU 1, the subscriber on CPU 0
    ->Args({0, 0, 0})    // policy "other" everywhere
    ->Args({0, 0, 2})    // ... atlasd and the subscriber on CPU 1
    ->Iterations(ScansPerRun())
    ->UseManualTime()
    ->Unit(benchmark::kMicrosecond);

}  // namespace
}  // namespace atlas
