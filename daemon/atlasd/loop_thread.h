#pragma once
// The live daemon's loop thread (live_daemon.h): one wake-up drains the device queues
// (input_drain.h; raw data republished when lcm.republish_raw), steps the atlas on the oldest
// pending scan, or sonar reading when localmap.sensors maps with the sonar (StepLoop: older ones
// beyond loop.max_pending_scans are dropped and counted; a sonar reading waits for the next
// wake-up, at most kIdleWait, as the sonar reader does not wake the loop), publishes through
// LcmSink, health every lcm.health_period_s, and hands a checkpoint to the store's writer thread
// every state.save_period_s (atlas_checkpoint.h). A reload (reload.h) is applied between steps.
// When idle it sleeps until the laser reader queues a scan (at most kIdleWait, for dead
// reckoning and health), never polling and never blocking on a device. It runs with the
// configured scheduling (policy, priority, affinity); when that is refused it carries on with
// the default scheduling and a warning.

#include <atomic>
#include <chrono>
#include <condition_variable>
#include <cstdint>
#include <lcm/lcm-cpp.hpp>
#include <memory>
#include <mutex>
#include <string>
#include <vector>

#include "core/atlas/atlas.h"
#include "core/mapper/step_loop.h"
#include "daemon/atlasd/atlas_checkpoint.h"
#include "daemon/atlasd/health_report.h"
#include "daemon/atlasd/input_drain.h"
#include "daemon/atlasd/lcm_sink.h"
#include "daemon/atlasd/live_daemon.h"
#include "daemon/lcm_in/lcm_input.h"
#include "daemon/lcm_out/atlas_publisher.h"
#include "daemon/store/atlas_store_writer.h"
#include "drivers/device/laser_reader.h"
#include "drivers/device/odometry_reader.h"
#include "drivers/device/sonar_reader.h"
#include "formats/config/daemon_options.h"

namespace atlas {

// The longest the loop sleeps without range data: dead-reckoning output (20 Hz), health periods
// and the heartbeat are checked at least this often.
inline constexpr auto kIdleWait = std::chrono::milliseconds(10);

// What the main thread and the loop thread share.
struct LoopShared {
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
  // kIdleWait passes), never polling.
  std::mutex range_mutex;
  std::condition_variable range_arrived;
  uint64_t range_queued = 0;  // under range_mutex
  void SignalRange();
  // Wakes the loop thread and makes it return.
  void Stop();
};

class LoopThread final : private DrainTarget {
 public:
  // `options` passed ValidateDerivedOptions; `shared` outlives the loop thread.
  LoopThread(const DaemonOptions& options, const LiveFlags& flags, LoopShared* shared);

  // On the main thread, before Run(): opens LCM, makes the atlas and resumes it from the store,
  // and starts the device readers, or with input.source = "lcm" the LCM input (no device is
  // opened). False when LCM cannot be opened (said on stderr).
  bool Start(Time start);
  // The thread's body: the steps until shared->stop, then the last checkpoint. An exception
  // (out of memory) ends it without a checkpoint and sets shared->loop_failed.
  void Run();
  // After Run() returned: stops the readers, then the store writer (which writes what is
  // queued), and prints what was saved and stepped.
  void Finish();

  // The enabled devices' (or LCM inputs') health and queues; from any thread.
  std::vector<DriverEntry> Drivers() const;

 private:
  bool StartLcmInput(const DriverLogSink& log);
  void RunSteps();
  void PublishHealth(Time now);
  void ApplyReload(const DaemonOptions& loaded);
  bool OpenStore();
  void SubmitCheckpoint();
  void OnOdometry(const OdometrySample& sample) override;
  void OnSonar(SonarReading& reading) override;
  void OnScan(LaserScan& scan) override;

  DaemonOptions options_;
  LiveFlags flags_;
  LoopShared* shared_;
  std::unique_ptr<lcm::LCM> lcm_;
  std::unique_ptr<AtlasPublisher> publisher_;
  std::unique_ptr<LcmSink> sink_;
  std::unique_ptr<Atlas> atlas_;
  std::unique_ptr<StepLoop> loop_;
  std::unique_ptr<LaserReader> laser_;
  std::unique_ptr<OdometryReader> odometry_;
  std::unique_ptr<SonarReader> sonar_;
  std::unique_ptr<LcmInput> lcm_input_;  // input.source = "lcm", instead of the readers
  std::unique_ptr<InputDrain> drain_;
  AtlasStore store_;
  std::unique_ptr<AtlasStoreWriter> writer_;  // null when the store could not be opened
  CheckpointBuilder checkpoints_;
  Time last_checkpoint_{};
  int64_t checkpoint_step_ = -1;  // atlas step count of the last checkpoint
  Time start_{};
  Time last_health_{}, last_line_{};
  bool republish_raw_ = false;
};

}  // namespace atlas
