#pragma once
// The subscriber of atlasd's LCM input mode (input.source = "lcm", docs/lcm.md "LCM input"):
// one thread handles one LCM instance subscribed to the laser and odometry channels, decodes
// each message with lcm_input_decode.h, stamps it with its arrival on the monotonic clock (LCM's
// receive time, ArrivalOnMonotonicClock), and
// pushes it into a bounded queue (SpscQueue: the oldest is dropped and counted when full), as
// the device readers do (drivers/device), so that the loop drains it the same way.
//
// Health, one DriverHealth per input as for a device: kConnecting until subscribed, then
// kRunning; kStalled ("no message on CHANNEL for N s") after stall_timeout without a message,
// kRunning again at the next one. A message that does not decode is counted (bad_messages),
// its reason is last_error and is said once per change; it never stops the input. A failed
// LCM handle is said and retried after a pause; an exception (out of memory) ends the thread
// with both inputs kFailed.

#include <atomic>
#include <functional>
#include <lcm/lcm-cpp.hpp>
#include <memory>
#include <optional>
#include <string>
#include <thread>

#include "daemon/lcm_in/lcm_input_decode.h"
#include "drivers/device/driver_health.h"
#include "drivers/device/driver_log.h"
#include "drivers/queue/spsc_queue.h"

namespace atlas {

struct LcmInputOptions {
  std::string url;            // the LCM provider to subscribe on
  bool laser_enabled = true;  // false: odometry only
  LaserMessageType laser_type = LaserMessageType::kLaserScan;
  OdometryMessageType odometry_type = OdometryMessageType::kOdometry;
  std::string laser_channel = "ATLAS_RAW_LASER";
  std::string odometry_channel = "ATLAS_RAW_ODOMETRY";
  LaserSetup laser;  // for the laser types that do not carry it
  size_t laser_queue_capacity = 8;
  size_t odometry_queue_capacity = 64;
  Duration stall_timeout = std::chrono::seconds(1);
  // > 0: the thread runs SCHED_FIFO at this priority (as the device readers), so that arrival
  // stamps are not delayed on a loaded machine; refused: said, and it runs normally.
  int realtime_priority = 0;
  // Called on the input thread right after a scan is queued (the loop's wake-up). May be empty.
  std::function<void()> on_scan;
  // Where each change of an input's state is said (DriverLog). May be empty.
  DriverLogSink log;
  std::string Validate() const;
};

class LcmInput {
 public:
  // `lcm`: the instance to subscribe on, handled by this input's thread alone; null: one is
  // opened on options.url by Start(). `options` must be valid.
  explicit LcmInput(const LcmInputOptions& options, std::unique_ptr<lcm::LCM> lcm = nullptr);
  ~LcmInput();
  LcmInput(const LcmInput&) = delete;
  LcmInput& operator=(const LcmInput&) = delete;

  // Opens LCM (unless given), subscribes and starts the thread. False with *error when LCM
  // cannot be opened.
  bool Start(std::string* error);
  // Idempotent; joins the thread.
  void Stop();

  SpscQueue<LaserScan>& laser_queue() { return laser_queue_; }
  SpscQueue<OdometrySample>& odometry_queue() { return odometry_queue_; }
  // From any thread.
  DriverHealth LaserHealth() const { return laser_.Health(laser_queue_.Dropped()); }
  DriverHealth OdometryHealth() const { return odometry_.Health(odometry_queue_.Dropped()); }

 private:
  // One subscribed channel's health, silence and log (its recorder is read from any thread).
  class Input {
   public:
    Input(std::string channel, const char* type, const LcmInputOptions& options);
    void Connecting();
    void Subscribed(Time now);
    // A message came at `now`; `error` is empty when it decoded.
    void Received(Time now, size_t bytes, const std::string& error);
    void CheckSilence(Time now);
    // Said once per text; `state`, when given, becomes the input's state.
    void Failed(const std::string& error, std::optional<DriverState> state = std::nullopt);
    void Stopped();
    DriverHealth Health(uint64_t drops) const;

   private:
    void Say(const std::optional<DriverLogLine>& line);
    std::string channel_;
    Duration stall_timeout_;
    DriverLogSink sink_;
    DriverHealthRecorder health_;
    DriverLog log_;
    Time last_message_{};
    bool stalled_ = false;
    bool delivered_ = false;
  };

  void Run();
  void OnLaser(const lcm::ReceiveBuffer* buffer, const std::string& channel);
  void OnOdometry(const lcm::ReceiveBuffer* buffer, const std::string& channel);

  LcmInputOptions options_;
  std::unique_ptr<lcm::LCM> lcm_;
  SpscQueue<LaserScan> laser_queue_;
  SpscQueue<OdometrySample> odometry_queue_;
  Input laser_;
  Input odometry_;
  std::thread thread_;
  std::atomic<bool> stop_{false};
};

}  // namespace atlas
