#include "daemon/atlasd/loop_thread.h"

#include <pthread.h>
#include <sched.h>

#include <cstdio>
#include <cstring>
#include <exception>
#include <thread>
#include <utility>

#include "daemon/atlasd/daemon_setup.h"
#include "daemon/atlasd/live_timing.h"
#include "daemon/atlasd/reload.h"
#include "daemon/lcm_out/lcm_convert.h"
#include "daemon/notify/stderr_log.h"

namespace atlas {
namespace {

void ApplyScheduling(const SchedulingOptions& s) {
  if (s.policy != SchedPolicy::kOther) {
    sched_param p{};
    p.sched_priority = s.priority;
    const int policy = s.policy == SchedPolicy::kFifo ? SCHED_FIFO : SCHED_RR;
    if (int e = pthread_setschedparam(pthread_self(), policy, &p); e != 0)
      LogToStderr(LogPriority::kWarning,
                  std::string("scheduling.policy/priority refused (") + std::strerror(e) +
                      "); the loop runs with the default policy (grant CAP_SYS_NICE or "
                      "LimitRTPRIO to allow it)");
  }
  if (!s.cpu_affinity.empty()) {
    cpu_set_t set;
    CPU_ZERO(&set);
    for (int c : s.cpu_affinity) CPU_SET(c, &set);
    if (int e = pthread_setaffinity_np(pthread_self(), sizeof(set), &set); e != 0)
      LogToStderr(LogPriority::kWarning, std::string("scheduling.cpu_affinity refused (") +
                                             std::strerror(e) + "); the loop may run on any CPU");
  }
}

}  // namespace

void LoopShared::SignalRange() {
  {
    std::lock_guard<std::mutex> lock(range_mutex);
    ++range_queued;
  }
  range_arrived.notify_one();
}

void LoopShared::Stop() {
  {
    std::lock_guard<std::mutex> lock(range_mutex);
    stop.store(true, std::memory_order_release);
  }
  range_arrived.notify_all();
}

LoopThread::LoopThread(const DaemonOptions& options, const LiveFlags& flags, LoopShared* shared)
    : options_(options), flags_(flags), shared_(shared) {}

bool LoopThread::Start(Time start) {
  start_ = start;
  lcm_ = std::make_unique<lcm::LCM>(options_.lcm.url);
  if (!lcm_->good()) {
    LogToStderr(LogPriority::kErr, "cannot open LCM at lcm.url = \"" + options_.lcm.url +
                                       "\" (is there a multicast route? see docs/atlasd.md)");
    return false;
  }
  // The messages' utime is microseconds since the epoch; said once, so that a stamp of atlasd's
  // monotonic clock (logs, the store) can be lined up with them.
  const EpochClock epoch = EpochClock::Capture();
  std::fprintf(stderr,
               "atlasd: LCM utime = CLOCK_MONOTONIC + %lld us (microseconds since the epoch)\n",
               static_cast<long long>(epoch.offset_us()));
  publisher_ = std::make_unique<AtlasPublisher>(lcm_.get(), options_.lcm.channels, epoch);
  sink_ = std::make_unique<LcmSink>(publisher_.get(), options_.lcm);
  republish_raw_ = options_.lcm.republish_raw;
  atlas_ = MakeAtlas(ToMapperSettings(options_));
  OpenStore();
  last_checkpoint_ = Now();
  // The loop steps the stamps a recording of the raw channels keeps, so that `atlasd --replay`
  // of the recording steps what the live loop stepped (core/mapper/step_loop.h).
  StepLoopOptions loop_options = ToStepLoopOptions(options_);
  loop_options.stamp_resolution = kUtimeResolution;
  loop_ = std::make_unique<StepLoop>(loop_options, ToMapperSettings(options_), atlas_.get());

  // Each driver's state changes, once each, with their reason (DriverLog).
  const DriverLogSink log = [](const DriverLogLine& l) { LogToStderr(l.priority, l.text); };
  if (options_.input.source == InputSource::kLcm) return StartLcmInput(log);
  OdometryReaderOptions oo = ToOdometryReaderOptions(options_);
  oo.reconnect.log = log;
  odometry_ = std::make_unique<OdometryReader>(oo);
  odometry_->Start();
  if (options_.laser.enabled) {
    LaserReaderOptions lo = ToLaserReaderOptions(options_);
    lo.on_scan = [this] { shared_->SignalRange(); };
    lo.reconnect.log = log;
    laser_ = std::make_unique<LaserReader>(lo);
    laser_->Start();
  }
  if (options_.sonar.enabled) {
    SonarReaderOptions so = ToSonarReaderOptions(options_);
    so.reconnect.log = log;
    // Readings the maps do not use are drained with the scans (republished when asked).
    if (options_.localmap.sensors != RangeSensors::kLaser)
      so.on_reading = [this] { shared_->SignalRange(); };
    sonar_ = std::make_unique<SonarReader>(so);
    sonar_->Start();
  }
  drain_ = std::make_unique<InputDrain>(&odometry_->queue(), sonar_ ? &sonar_->queue() : nullptr,
                                        laser_ ? &laser_->queue() : nullptr);
  return true;
}

// input.source = "lcm": the LCM input in place of the device readers.
bool LoopThread::StartLcmInput(const DriverLogSink& log) {
  LcmInputOptions io = ToLcmInputOptions(options_);
  io.on_scan = [this] { shared_->SignalRange(); };
  io.log = log;
  lcm_input_ = std::make_unique<LcmInput>(io);
  std::string error;
  if (!lcm_input_->Start(&error)) {
    LogToStderr(LogPriority::kErr, error + " (is there a multicast route? see docs/atlasd.md)");
    return false;
  }
  drain_ =
      std::make_unique<InputDrain>(&lcm_input_->odometry_queue(), nullptr,
                                   options_.laser.enabled ? &lcm_input_->laser_queue() : nullptr);
  return true;
}

std::vector<DriverEntry> LoopThread::Drivers() const {
  std::vector<DriverEntry> d;
  if (lcm_input_) {
    const auto entry = [](const char* name, const DriverHealth& h, const auto& queue) {
      return DriverEntry{name, h, static_cast<int>(queue.SizeApprox()),
                         static_cast<int>(queue.capacity())};
    };
    if (options_.laser.enabled)
      d.push_back(entry("laser", lcm_input_->LaserHealth(), lcm_input_->laser_queue()));
    d.push_back(entry("odometry", lcm_input_->OdometryHealth(), lcm_input_->odometry_queue()));
    return d;
  }
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

void LoopThread::OnOdometry(const OdometrySample& sample) {
  if (republish_raw_) publisher_->RawOdometry(sample);
  loop_->AddOdometry(sample);
}

// localmap.sensors: the maps are stepped with the laser, the sonar, or both.
void LoopThread::OnSonar(SonarReading& reading) {
  if (republish_raw_) publisher_->RawSonar(reading);
  if (options_.localmap.sensors != RangeSensors::kLaser) loop_->AddSonar(std::move(reading));
}

void LoopThread::OnScan(LaserScan& scan) {
  if (republish_raw_) publisher_->RawLaser(scan);
  if (options_.localmap.sensors != RangeSensors::kSonar) loop_->AddScan(std::move(scan));
}

void LoopThread::PublishHealth(Time now) {
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
  const atlasd::health_t h = MakeHealthMessage(in);
  publisher_->Health(h);
  {
    std::lock_guard<std::mutex> lock(shared_->mutex);
    shared_->status = h.status;
  }
  if (!flags_.quiet &&
      Due(now, last_line_,
          HealthLinePeriod(flags_.health_line_period_s, options_.lcm.health_period_s))) {
    last_line_ = now;
    std::fprintf(stderr, "atlasd: %s\n", h.status.c_str());
  }
}

void LoopThread::ApplyReload(const DaemonOptions& loaded) {
  const ReloadPlan plan = PlanReload(options_, loaded);
  std::string refused;
  options_ = plan.with_atlas;
  if (plan.rebuild_atlas) {
    AtlasRebuild rebuilt = RebuildAtlas(*atlas_, plan.with_atlas);
    if (rebuilt.atlas) {
      loop_->ReplaceAtlas(rebuilt.atlas.get(), rebuilt.settings);
      atlas_ = std::move(rebuilt.atlas);
    } else {
      refused = rebuilt.refused;
      options_ = plan.without_atlas;
    }
  }
  republish_raw_ = options_.lcm.republish_raw;
  loop_->SetStepBudget(ToStepLoopOptions(options_).step_budget);
  sink_->SetPeriods(options_.lcm);
  std::fprintf(stderr, "atlasd: %s\n", ReloadReport(plan, refused).c_str());
}

// Opens the store in state.directory and resumes the saved atlas. False only when the store is
// unusable (the daemon then maps without saving, and says so).
bool LoopThread::OpenStore() {
  const StoreOpenResult opened = store_.Open(options_.state.directory);
  LogToStderr(opened.ok() ? LogPriority::kInfo : LogPriority::kWarning, opened.message);
  if (!opened.ok()) {
    LogToStderr(LogPriority::kWarning, "the atlas will NOT be saved (the reason is above)");
    return false;
  }
  const ResumeResult resumed = ResumeFromStore(&store_, atlas_.get(), &checkpoints_);
  std::fprintf(stderr, "atlasd: %s\n", resumed.message.c_str());
  if (resumed.outcome == ResumeOutcome::kFailed) return false;
  if (resumed.outcome == ResumeOutcome::kResumed) checkpoint_step_ = atlas_->StepCount();
  writer_ = std::make_unique<AtlasStoreWriter>(&store_, options_.state.writer_queue_capacity);
  writer_->Start();
  return true;
}

// The atlas image and changed rows go to the writer thread, which alone touches SQLite.
void LoopThread::SubmitCheckpoint() {
  if (!writer_ || atlas_->StepCount() == checkpoint_step_) return;
  checkpoint_step_ = atlas_->StepCount();
  writer_->Submit(checkpoints_.Make(*atlas_));
}

void LoopThread::Run() {
  ApplyScheduling(options_.scheduling);
  shared_->loop_running.store(true);
  // The steps throw nothing on input (typed results); what is left (out of memory) ends the
  // loop without a last checkpoint, whose atlas could be half-updated: the store keeps the one
  // before, and the process exits so that systemd restarts atlasd from it.
  try {
    RunSteps();
  } catch (const std::exception& e) {
    LogToStderr(LogPriority::kErr, std::string("the step loop stopped: ") + e.what());
    shared_->loop_running.store(false);
    shared_->loop_failed.store(true, std::memory_order_release);
    return;
  }
  SubmitCheckpoint();  // the last steps, saved by Finish()
  shared_->loop_running.store(false);
}

void LoopThread::RunSteps() {
  while (!shared_->stop.load(std::memory_order_acquire)) {
    const Time now = Now();
    if (shared_->stall_until_ns.load() > now.time_since_epoch().count()) {
      std::this_thread::sleep_for(std::chrono::milliseconds(20));  // test stall: no heartbeat
      continue;
    }
    shared_->heartbeat_ns.store(now.time_since_epoch().count(), std::memory_order_release);
    {
      std::unique_lock<std::mutex> lock(shared_->mutex, std::try_to_lock);
      if (lock.owns_lock() && shared_->reload_pending) {
        shared_->reload_pending = false;
        DaemonOptions loaded = shared_->reloaded;
        lock.unlock();
        ApplyReload(loaded);
      }
    }
    uint64_t range_seen;
    {
      std::lock_guard<std::mutex> lock(shared_->range_mutex);
      range_seen = shared_->range_queued;
    }
    drain_->Drain(this);
    const bool stepped = loop_->StepOne(sink_.get());
    if (stepped && Due(now, last_checkpoint_, SecondsToDuration(options_.state.save_period_s))) {
      last_checkpoint_ = now;
      SubmitCheckpoint();
    }
    if (Due(now, last_health_, SecondsToDuration(options_.lcm.health_period_s))) {
      last_health_ = now;
      PublishHealth(now);
    }
    if (!stepped) {
      std::unique_lock<std::mutex> lock(shared_->range_mutex);
      shared_->range_arrived.wait_for(lock, kIdleWait, [&] {
        return shared_->range_queued != range_seen || shared_->stop.load(std::memory_order_acquire);
      });
    }
  }
}

void LoopThread::Finish() {
  if (lcm_input_) lcm_input_->Stop();
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
}

}  // namespace atlas
