#include "daemon/atlasd/live_daemon.h"

#include <pthread.h>
#include <sched.h>
#include <signal.h>
#include <sys/mman.h>
#include <unistd.h>

#include <algorithm>
#include <atomic>
#include <cerrno>
#include <cmath>
#include <condition_variable>
#include <cstdio>
#include <cstring>
#include <exception>
#include <fstream>
#include <memory>
#include <mutex>
#include <thread>

#include "daemon/atlasd/atlas_checkpoint.h"
#include "daemon/atlasd/daemon_setup.h"
#include "daemon/atlasd/health_report.h"
#include "daemon/config/config_loader.h"
#include "daemon/lcm_out/atlas_publisher.h"
#include "daemon/notify/service_notifier.h"
#include "daemon/store/atlas_store_writer.h"

namespace atlas {
namespace {

// sysexits.h EX_SOFTWARE: the step loop stopped on an internal error (systemd restarts atlasd).
constexpr int kExitSoftware = 70;

// Why the running atlas's image does not load into `rebuilt`, made with the new parameters
// (Atlas::Deserialize refuses what they do not bound: more hypotheses than max_hypotheses, a map
// above map_capacity, a juvenile's w scans not below its probation).
std::string Misfit(const Atlas& running, const Atlas& rebuilt, int map_capacity) {
  std::string why;
  const auto add = [&why](const std::string& s) { why += (why.empty() ? "" : "; ") + s; };
  const AtlasOptions& o = rebuilt.Options();
  const int alive = static_cast<int>(running.Hypotheses().size());
  if (alive > o.max_hypotheses)
    add(std::to_string(alive) + " hypotheses alive, above atlas.max_hypotheses " +
        std::to_string(o.max_hypotheses));
  int features = 0;
  for (FrameId f = 0; f < running.Graph().FrameCount(); ++f)
    features = std::max(features, running.Graph().Frame(f).map->Complexity());
  size_t z = 0;
  for (const Hypothesis& h : running.Hypotheses()) {
    if (h.trial_map) features = std::max(features, h.trial_map->Complexity());
    z = std::max(z, h.z.size());
  }
  if (features > map_capacity)
    add("a map holds " + std::to_string(features) + " features, above atlas.map_capacity " +
        std::to_string(map_capacity) + " (a capacity can grow on reload, not shrink)");
  if (z >= static_cast<size_t>(o.lifecycle.probation_scans))
    add("a juvenile holds " + std::to_string(z) + " scans for w, not below its probation of " +
        std::to_string(o.lifecycle.probation_scans) + " steps");
  return why.empty() ? "hypotheses alive: " + std::to_string(alive) : why;
}

Duration SecondsToDuration(double s) {
  return std::chrono::duration_cast<Duration>(std::chrono::duration<double>(s));
}

// Publishes the loop's outputs at their periods (wall-clock periods of the loop thread).
class LcmSink final : public StepSink {
 public:
  LcmSink(AtlasPublisher* publisher, const LcmOptions& o) : publisher_(publisher) { SetPeriods(o); }
  void SetPeriods(const LcmOptions& o) {
    graph_period_ = SecondsToDuration(o.graph_period_s);
    map_period_ = SecondsToDuration(o.local_map_period_s);
  }
  void OnPose(Time stamp, const DominantOutput& pose, PoseSource) override {
    publisher_->Pose(stamp, pose);
  }
  void OnStep(Time stamp, const Atlas& atlas) override {
    const Time now = Now();
    if (now - last_graph_ >= graph_period_) {
      last_graph_ = now;
      publisher_->Graph(stamp, atlas);
      publisher_->Hypotheses(stamp, atlas);
    }
    if (now - last_map_ >= map_period_) {
      last_map_ = now;
      publisher_->LocalMap(stamp, atlas);
    }
  }

 private:
  AtlasPublisher* publisher_;
  Duration graph_period_{}, map_period_{};
  Time last_graph_{}, last_map_{};
};

struct Shared {
  std::atomic<bool> stop{false};
  std::atomic<int64_t> heartbeat_ns{0};
  std::atomic<bool> loop_running{false};
  std::atomic<bool> loop_failed{false};  // the loop thread stopped on an exception
  std::atomic<int64_t> stall_until_ns{0};
  std::mutex mutex;
  std::string status;  // one-line summary, under mutex
  bool reload_pending = false;
  DaemonOptions reloaded;  // under mutex
  // Range data queued by the laser reader, and by the sonar reader when the local maps use the
  // sonar: the loop thread sleeps on `range_arrived` until a scan or a reading comes (or
  // kIdleWait passes, for dead reckoning and health), never polling.
  std::mutex range_mutex;
  std::condition_variable range_arrived;
  uint64_t range_queued = 0;  // under range_mutex
  void SignalRange() {
    {
      std::lock_guard<std::mutex> lock(range_mutex);
      ++range_queued;
    }
    range_arrived.notify_one();
  }
};

// The loop takes every stamp at the resolution of the raw channels (whole microseconds, utime),
// so that `atlasd --replay` of the republished channels feeds the StepLoop exactly what it had.
template <typename T>
void ToRawResolution(T* item) {
  item->stamp = FromUtime(ToUtime(item->stamp));
}

// The longest the loop sleeps without range data: dead-reckoning output (20 Hz), health periods and
// the heartbeat are checked at least this often.
constexpr auto kIdleWait = std::chrono::milliseconds(10);

void ApplyScheduling(const SchedulingOptions& s) {
  if (s.policy != SchedPolicy::kOther) {
    sched_param p{};
    p.sched_priority = s.priority;
    const int policy = s.policy == SchedPolicy::kFifo ? SCHED_FIFO : SCHED_RR;
    if (int e = pthread_setschedparam(pthread_self(), policy, &p); e != 0)
      std::fprintf(stderr,
                   "atlasd: warning: scheduling.policy/priority refused (%s); the loop runs "
                   "with the default policy (grant CAP_SYS_NICE or LimitRTPRIO to allow it)\n",
                   std::strerror(e));
  }
  if (!s.cpu_affinity.empty()) {
    cpu_set_t set;
    CPU_ZERO(&set);
    for (int c : s.cpu_affinity) CPU_SET(c, &set);
    if (int e = pthread_setaffinity_np(pthread_self(), sizeof(set), &set); e != 0)
      std::fprintf(stderr,
                   "atlasd: warning: scheduling.cpu_affinity refused (%s); the loop may run on "
                   "any CPU\n",
                   std::strerror(e));
  }
}

class LiveDaemon {
 public:
  LiveDaemon(const DaemonOptions& o, const LiveFlags& f) : options_(o), flags_(f) {}

  int Run();

 private:
  void LoopThread();
  void RunLoop();  // the steps, until shared_.stop
  void Drain();
  void PublishHealth(Time now);
  std::vector<DriverEntry> Drivers() const;
  void ApplyReload(const DaemonOptions& loaded);
  std::string ReloadAtlas(const DaemonOptions& candidate);
  bool OpenStore();
  void SubmitCheckpoint();

  DaemonOptions options_;
  LiveFlags flags_;
  Shared shared_;
  std::unique_ptr<lcm::LCM> lcm_;
  std::unique_ptr<AtlasPublisher> publisher_;
  std::unique_ptr<LcmSink> sink_;
  std::unique_ptr<Atlas> atlas_;
  std::unique_ptr<StepLoop> loop_;
  std::unique_ptr<LaserReader> laser_;
  std::unique_ptr<OdometryReader> odometry_;
  std::unique_ptr<SonarReader> sonar_;
  std::vector<SonarReading> drained_sonar_;  // one drain, capacity reserved at start
  std::vector<LaserScan> drained_scans_;
  AtlasStore store_;
  std::unique_ptr<AtlasStoreWriter> writer_;  // null when the store could not be opened
  CheckpointBuilder checkpoints_;
  Time last_checkpoint_{};
  int64_t checkpoint_step_ = -1;  // atlas step count of the last checkpoint
  Time start_{};
  Time last_health_{}, last_line_{};
  bool republish_raw_ = false;
  ServiceNotifier notifier_;
};

std::vector<DriverEntry> LiveDaemon::Drivers() const {
  std::vector<DriverEntry> d;
  if (laser_)
    d.push_back({"laser", laser_->Health(), static_cast<int>(laser_->queue().SizeApprox()),
                 static_cast<int>(laser_->queue().capacity())});
  if (odometry_)
    d.push_back({"odometry", odometry_->Health(), static_cast<int>(odometry_->queue().SizeApprox()),
                 static_cast<int>(odometry_->queue().capacity())});
  if (sonar_)
    d.push_back({"sonar", sonar_->Health(), static_cast<int>(sonar_->queue().SizeApprox()),
                 static_cast<int>(sonar_->queue().capacity())});
  return d;
}

void LiveDaemon::Drain() {
  OdometrySample o;
  while (odometry_ && odometry_->Pop(&o)) {
    ToRawResolution(&o);
    if (republish_raw_) publisher_->RawOdometry(o);
    loop_->AddOdometry(o);
  }
  // The readings and scans drained together go to the loop (and are republished) in stamp
  // order; the loop steps in the order they are added, so a recording of the raw channels
  // holds the step order (step_loop.h). At most one queue's capacity of each per drain.
  drained_sonar_.clear();
  drained_scans_.clear();
  SonarReading s;
  while (sonar_ && drained_sonar_.size() < drained_sonar_.capacity() && sonar_->Pop(&s)) {
    ToRawResolution(&s);
    drained_sonar_.push_back(std::move(s));
  }
  LaserScan scan;
  while (laser_ && drained_scans_.size() < drained_scans_.capacity() && laser_->Pop(&scan)) {
    ToRawResolution(&scan);
    drained_scans_.push_back(std::move(scan));
  }
  // localmap.sensors: the maps are stepped with the laser, the sonar, or both.
  const LocalMapSensors maps_use = options_.localmap.sensors;
  InStampOrder(
      drained_sonar_, drained_scans_,
      [&](SonarReading& r) {
        if (republish_raw_) publisher_->RawSonar(r);
        if (maps_use != LocalMapSensors::kLaser) loop_->AddSonar(std::move(r));
      },
      [&](LaserScan& l) {
        if (republish_raw_) publisher_->RawLaser(l);
        if (maps_use != LocalMapSensors::kSonar) loop_->AddScan(std::move(l));
      });
}

void LiveDaemon::PublishHealth(Time now) {
  HealthInputs in;
  in.now = now;
  in.start = start_;
  in.loop = loop_.get();
  in.period = loop_->TakePeriod();
  in.step_budget_ms = options_.loop.step_budget_ms;
  in.drivers = Drivers();
  if (writer_) {
    const StoreWriterStats st = writer_->Stats();
    in.store_saved = static_cast<int64_t>(st.saved);
    in.store_dropped = static_cast<int64_t>(st.coalesced);
    in.store_errors = static_cast<int64_t>(st.errors);
  }
  const atlas::health_t h = MakeHealthMessage(in);
  publisher_->Health(h);
  {
    std::lock_guard<std::mutex> lock(shared_.mutex);
    shared_.status = h.status;
  }
  const double line_period =
      flags_.health_line_period_s > 0 ? flags_.health_line_period_s : options_.lcm.health_period_s;
  if (!flags_.quiet &&
      now - last_line_ >= SecondsToDuration(line_period) - std::chrono::milliseconds(5)) {
    last_line_ = now;
    std::fprintf(stderr, "atlasd: %s\n", h.status.c_str());
  }
}

// Atlas and noise parameters: the running atlas is rebuilt from its own image by an atlas made
// with the new settings (graph, maps and hypotheses kept; new options from the next step on).
// Refused, with the old atlas kept and the reason logged, when the image does not fit the new
// settings (more hypotheses alive than the new atlas.max_hypotheses, a map above a smaller
// atlas.map_capacity, a juvenile's w scans past a shorter probation).
std::string LiveDaemon::ReloadAtlas(const DaemonOptions& candidate) {
  const MapperSettings settings = ToMapperSettings(candidate);
  if (std::string e = ValidateMapperSettings(settings); !e.empty()) return e;
  std::unique_ptr<Atlas> rebuilt = MakeAtlas(settings);
  if (!rebuilt->Deserialize(atlas_->Serialize()))
    return "the running atlas does not fit the new parameters (" +
           Misfit(*atlas_, *rebuilt, settings.map_capacity) + ")";
  loop_->ReplaceAtlas(rebuilt.get(), settings);
  atlas_ = std::move(rebuilt);
  return "";
}

void LiveDaemon::ApplyReload(const DaemonOptions& loaded) {
  const ReloadDiff diff = DiffForReload(options_, loaded);
  std::string applied, refused, restart;
  bool atlas_changed = false;
  for (const auto& k : diff.reloadable) {
    if (k.rfind("atlas.", 0) == 0 || k.rfind("noise.", 0) == 0) {
      atlas_changed = true;
    } else {
      applied += " " + k;
    }
  }
  for (const auto& k : diff.needs_restart) restart += " " + k;
  if (atlas_changed) {
    DaemonOptions candidate = options_;
    candidate.atlas = loaded.atlas;
    candidate.noise = loaded.noise;
    if (std::string why = ReloadAtlas(candidate); why.empty()) {
      options_.atlas = loaded.atlas;
      options_.noise = loaded.noise;
      for (const auto& k : diff.reloadable)
        if (k.rfind("atlas.", 0) == 0 || k.rfind("noise.", 0) == 0) applied += " " + k;
    } else {
      refused = " atlas/noise parameters refused (" + why + "), the running ones stay;";
    }
  }
  options_.loop.step_budget_ms = loaded.loop.step_budget_ms;
  options_.lcm.health_period_s = loaded.lcm.health_period_s;
  options_.lcm.graph_period_s = loaded.lcm.graph_period_s;
  options_.lcm.local_map_period_s = loaded.lcm.local_map_period_s;
  options_.lcm.republish_raw = loaded.lcm.republish_raw;
  options_.state.save_period_s = loaded.state.save_period_s;
  republish_raw_ = loaded.lcm.republish_raw;
  loop_->SetStepBudget(ToStepLoopOptions(options_).step_budget);
  sink_->SetPeriods(options_.lcm);
  std::fprintf(
      stderr, "atlasd: reload: applied:%s;%s%s\n", applied.empty() ? " (nothing)" : applied.c_str(),
      refused.c_str(),
      restart.empty() ? "" : (" need a restart (unchanged until then):" + restart).c_str());
}

// Opens the store in state.directory and resumes the saved atlas. False only when the store is
// unusable (the daemon then maps without saving, and says so).
bool LiveDaemon::OpenStore() {
  const StoreOpenResult opened = store_.Open(options_.state.directory);
  std::fprintf(stderr, "atlasd: %s\n", opened.message.c_str());
  if (!opened.ok()) {
    std::fprintf(stderr, "atlasd: warning: the atlas will NOT be saved (the reason is above)\n");
    return false;
  }
  const ResumeResult resumed = ResumeFromStore(&store_, atlas_.get());
  std::fprintf(stderr, "atlasd: %s\n", resumed.message.c_str());
  if (resumed.outcome == ResumeOutcome::kFailed) return false;
  if (resumed.outcome == ResumeOutcome::kResumed) checkpoint_step_ = atlas_->StepCount();
  writer_ = std::make_unique<AtlasStoreWriter>(&store_, options_.state.writer_queue_capacity);
  writer_->Start();
  return true;
}

// On the loop thread: the atlas image and changed rows go to the writer thread, which alone
// touches SQLite.
void LiveDaemon::SubmitCheckpoint() {
  if (!writer_ || atlas_->StepCount() == checkpoint_step_) return;
  checkpoint_step_ = atlas_->StepCount();
  writer_->Submit(checkpoints_.Make(*atlas_));
}

void LiveDaemon::LoopThread() {
  ApplyScheduling(options_.scheduling);
  shared_.loop_running.store(true);
  // The steps throw nothing on input (typed results); what is left (out of memory) ends the
  // loop without a last checkpoint, whose atlas could be half-updated: the store keeps the one
  // before, and Run() exits so that systemd restarts atlasd from it.
  try {
    RunLoop();
  } catch (const std::exception& e) {
    std::fprintf(stderr, "atlasd: the step loop stopped: %s\n", e.what());
    shared_.loop_running.store(false);
    shared_.loop_failed.store(true, std::memory_order_release);
    return;
  }
  SubmitCheckpoint();  // the last steps, saved by Run() before it returns
  shared_.loop_running.store(false);
}

void LiveDaemon::RunLoop() {
  while (!shared_.stop.load(std::memory_order_acquire)) {
    const Time now = Now();
    if (shared_.stall_until_ns.load() > now.time_since_epoch().count()) {
      std::this_thread::sleep_for(std::chrono::milliseconds(20));  // test stall: no heartbeat
      continue;
    }
    shared_.heartbeat_ns.store(now.time_since_epoch().count(), std::memory_order_release);
    {
      std::unique_lock<std::mutex> lock(shared_.mutex, std::try_to_lock);
      if (lock.owns_lock() && shared_.reload_pending) {
        shared_.reload_pending = false;
        DaemonOptions loaded = shared_.reloaded;
        lock.unlock();
        ApplyReload(loaded);
      }
    }
    uint64_t range_seen;
    {
      std::lock_guard<std::mutex> lock(shared_.range_mutex);
      range_seen = shared_.range_queued;
    }
    Drain();
    const bool stepped = loop_->StepOne(sink_.get());
    if (stepped && now - last_checkpoint_ >= SecondsToDuration(options_.state.save_period_s)) {
      last_checkpoint_ = now;
      SubmitCheckpoint();
    }
    if (now - last_health_ >= SecondsToDuration(options_.lcm.health_period_s)) {
      last_health_ = now;
      PublishHealth(now);
    }
    if (!stepped) {
      std::unique_lock<std::mutex> lock(shared_.range_mutex);
      shared_.range_arrived.wait_for(lock, kIdleWait, [&] {
        return shared_.range_queued != range_seen || shared_.stop.load(std::memory_order_acquire);
      });
    }
  }
}

int LiveDaemon::Run() {
  start_ = Now();
  if (std::string e = ValidateDerivedOptions(options_); !e.empty()) {
    std::fprintf(stderr, "atlasd: configuration rejected:\n%s", e.c_str());
    return kExitConfigError;
  }
  // Signals are handled by the main thread only (sigtimedwait); block them before any thread.
  sigset_t signals;
  sigemptyset(&signals);
  for (int s : {SIGTERM, SIGINT, SIGHUP, SIGUSR1}) sigaddset(&signals, s);
  pthread_sigmask(SIG_BLOCK, &signals, nullptr);

  if (options_.scheduling.mlockall && mlockall(MCL_CURRENT | MCL_FUTURE) != 0)
    std::fprintf(stderr,
                 "atlasd: warning: scheduling.mlockall refused (%s); memory may be paged out "
                 "(raise LimitMEMLOCK or grant CAP_IPC_LOCK)\n",
                 std::strerror(errno));

  lcm_ = std::make_unique<lcm::LCM>(options_.lcm.url);
  if (!lcm_->good()) {
    std::fprintf(stderr,
                 "atlasd: cannot open LCM at lcm.url = \"%s\" (is there a multicast route? see "
                 "docs/atlasd.md)\n",
                 options_.lcm.url.c_str());
    return 1;
  }
  publisher_ = std::make_unique<AtlasPublisher>(lcm_.get(), options_.lcm.channels);
  sink_ = std::make_unique<LcmSink>(publisher_.get(), options_.lcm);
  republish_raw_ = options_.lcm.republish_raw;
  atlas_ = MakeAtlas(ToMapperSettings(options_));
  OpenStore();
  last_checkpoint_ = Now();
  loop_ = std::make_unique<StepLoop>(ToStepLoopOptions(options_), ToMapperSettings(options_),
                                     atlas_.get());

  odometry_ = std::make_unique<OdometryReader>(ToOdometryReaderOptions(options_));
  odometry_->Start();
  if (options_.laser.enabled) {
    LaserReaderOptions lo = ToLaserReaderOptions(options_);
    lo.on_scan = [this] { shared_.SignalRange(); };
    laser_ = std::make_unique<LaserReader>(lo);
    drained_scans_.reserve(laser_->queue().capacity());
    laser_->Start();
  }
  if (options_.sonar.enabled) {
    SonarReaderOptions so = ToSonarReaderOptions(options_);
    // Readings the maps do not use are drained with the scans (republished when asked).
    if (options_.localmap.sensors != LocalMapSensors::kLaser)
      so.on_reading = [this] { shared_.SignalRange(); };
    sonar_ = std::make_unique<SonarReader>(so);
    drained_sonar_.reserve(sonar_->queue().capacity());
    sonar_->Start();
  }
  std::thread loop_thread([this] { LoopThread(); });

  // READY once every device runs (or after ready_timeout: a missing device is a fault the
  // daemon reports and survives, not a reason to be killed by systemd's start timeout).
  const Time ready_deadline = start_ + SecondsToDuration(flags_.ready_timeout_s);
  bool ready = false;
  const auto watchdog = ServiceNotifier::WatchdogInterval();
  const Duration ping_period = watchdog.count() > 0
                                   ? std::chrono::duration_cast<Duration>(watchdog / 2)
                                   : Duration(std::chrono::seconds(1));
  const Duration heartbeat_max = std::min<Duration>(ping_period, std::chrono::seconds(1));
  Time last_ping{};
  std::string last_status;
  int exit_code = 0;
  for (;;) {
    timespec timeout{0, 50 * 1000 * 1000};
    siginfo_t info;
    const int sig = sigtimedwait(&signals, &info, &timeout);
    const Time now = Now();
    if (sig == SIGTERM || sig == SIGINT) break;
    if (shared_.loop_failed.load(std::memory_order_acquire)) {
      std::fprintf(stderr,
                   "atlasd: exiting: the atlas is saved up to its last checkpoint (%.1f s or "
                   "less ago), from which the next start resumes\n",
                   options_.state.save_period_s);
      exit_code = kExitSoftware;
      break;
    }
    if (sig == SIGHUP) {
      ConfigResult r = LoadConfigFile(flags_.config_path, ValidateDerivedOptions);
      if (!r.ok()) {
        std::fprintf(stderr, "atlasd: reload refused, the running configuration stays:\n");
        for (const auto& e : r.errors) std::fprintf(stderr, "  %s\n", e.ToString().c_str());
      } else {
        std::lock_guard<std::mutex> lock(shared_.mutex);
        shared_.reloaded = r.options;
        shared_.reload_pending = true;
      }
    }
    if (sig == SIGUSR1) {
      if (flags_.debug_stall_on_usr1) {
        std::fprintf(stderr, "atlasd: SIGUSR1: stalling the loop for %.1f s (test hook)\n",
                     flags_.stall_seconds);
        shared_.stall_until_ns.store(
            (now + SecondsToDuration(flags_.stall_seconds)).time_since_epoch().count());
      }
    }
    if (!ready) {
      bool all = shared_.loop_running.load();
      for (const auto& d : Drivers()) all = all && d.health.state == DriverState::kRunning;
      if (all || now >= ready_deadline) {
        ready = true;
        notifier_.Ready();
        if (!all) std::fprintf(stderr, "atlasd: ready without every device (see health)\n");
      }
    }
    const bool healthy =
        now - Time(Duration(shared_.heartbeat_ns.load(std::memory_order_acquire))) < heartbeat_max;
    if (ready && now - last_ping >= ping_period) {
      last_ping = now;
      std::string status;
      {
        std::lock_guard<std::mutex> lock(shared_.mutex);
        status = shared_.status;
      }
      if (!status.empty() && status != last_status) {
        notifier_.Status(status);
        last_status = status;
      }
      if (healthy && watchdog.count() > 0) notifier_.Watchdog();
      if (!healthy) {
        notifier_.Status("loop stalled: no watchdog ping");
        last_status.clear();
      }
    }
  }
  notifier_.Stopping();
  std::fprintf(stderr, "atlasd: stopping\n");
  {
    std::lock_guard<std::mutex> lock(shared_.range_mutex);
    shared_.stop.store(true, std::memory_order_release);
  }
  shared_.range_arrived.notify_all();
  loop_thread.join();
  if (laser_) laser_->Stop();
  if (odometry_) odometry_->Stop();
  if (sonar_) sonar_->Stop();
  if (writer_) {
    writer_->Stop();  // writes what is queued, the last checkpoint included
    const StoreWriterStats st = writer_->Stats();
    std::fprintf(stderr, "atlasd: saved %llu checkpoints to %s (%llu merged, %llu errors%s%s)\n",
                 static_cast<unsigned long long>(st.saved), store_.path().c_str(),
                 static_cast<unsigned long long>(st.coalesced),
                 static_cast<unsigned long long>(st.errors), st.last_error.empty() ? "" : ": ",
                 st.last_error.c_str());
  }
  std::fprintf(stderr, "atlasd: stopped after %lld steps\n",
               static_cast<long long>(loop_->steps()));
  return exit_code;
}

}  // namespace

int RunLiveDaemon(const DaemonOptions& options, const LiveFlags& flags) {
  LiveDaemon d(options, flags);
  return d.Run();
}

}  // namespace atlas
