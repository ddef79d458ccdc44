#include "daemon/lcm_in/lcm_input.h"

#include <chrono>
#include <cmath>
#include <exception>
#include <span>

#include "drivers/device/realtime_priority.h"

namespace atlas {

std::string LcmInputOptions::Validate() const {
  if (url.empty()) return "lcm input: url is empty";
  if (laser_channel.empty() || odometry_channel.empty()) return "lcm input: a channel is empty";
  if (laser_enabled && laser_channel == odometry_channel)
    return "lcm input: the laser and odometry channels are the same";
  if (laser_queue_capacity < 1 || odometry_queue_capacity < 1)
    return "lcm input: queue capacities must be >= 1";
  if (stall_timeout <= Duration::zero()) return "lcm input: stall_timeout must be > 0";
  if (realtime_priority < 0 || realtime_priority > 99)
    return "lcm input: realtime_priority must be 0 (off) or 1..99";
  if (!(laser.max_range > 0.0f) || !std::isfinite(laser.max_range))
    return "lcm input: laser max_range must be > 0";
  return "";
}

LcmInput::Input::Input(std::string channel, const char* type, const LcmInputOptions& options)
    : channel_(channel),
      stall_timeout_(options.stall_timeout),
      sink_(options.log),
      health_("lcm:" + channel + " (" + type + ")"),
      log_("lcm:" + channel) {}

void LcmInput::Input::Say(const std::optional<DriverLogLine>& line) {
  if (line && sink_) sink_(*line);
}

void LcmInput::Input::Connecting() {
  health_.SetState(DriverState::kConnecting);
  Say(log_.Connecting());
}

void LcmInput::Input::Subscribed(Time now) {
  last_message_ = now;  // the silence is counted from the subscription
  health_.SetState(DriverState::kRunning);
}

void LcmInput::Input::Received(Time now, size_t bytes, const std::string& error) {
  health_.bytes.fetch_add(bytes, std::memory_order_relaxed);
  last_message_ = now;
  if (stalled_) {
    stalled_ = false;
    health_.SetState(DriverState::kRunning);
    Say(log_.Resumed());
  }
  if (!error.empty()) {
    health_.bad_messages.fetch_add(1, std::memory_order_relaxed);
    const std::string text = channel_ + ": " + error;
    health_.SetError(text);
    Say(log_.Condition(LogPriority::kWarning, text));
    return;
  }
  health_.samples.fetch_add(1, std::memory_order_relaxed);
  health_.CountMessage(now);  // counts it in messages
  if (!delivered_) {
    delivered_ = true;
    Say(log_.Delivering());
  }
}

void LcmInput::Input::CheckSilence(Time now) {
  const Duration silent = now - last_message_;
  if (stalled_ || silent < stall_timeout_) return;
  stalled_ = true;
  health_.stalls.fetch_add(1, std::memory_order_relaxed);
  health_.SetState(DriverState::kStalled);
  const std::string why = "no message on " + channel_ + " for " +
                          std::to_string(ToSeconds(silent)).substr(0, 4) +
                          " s (is its publisher running, on this lcm.url?)";
  health_.SetError(why);
  // Silent from the start (a wrong channel, no publisher) is said too, once.
  Say(delivered_ ? log_.Stalled(why) : log_.Condition(LogPriority::kWarning, why));
}

void LcmInput::Input::Failed(const std::string& error, std::optional<DriverState> state) {
  health_.SetError(error);
  if (state) health_.SetState(*state);
  Say(log_.Condition(LogPriority::kErr, error));
}

void LcmInput::Input::Stopped() {
  health_.SetState(DriverState::kStopped);
  Say(log_.Stopped());
}

DriverHealth LcmInput::Input::Health(uint64_t drops) const {
  DriverHealth h = health_.Snapshot();
  h.drops = drops;
  return h;
}

LcmInput::LcmInput(const LcmInputOptions& options, std::unique_ptr<lcm::LCM> lcm)
    : options_(options),
      lcm_(std::move(lcm)),
      laser_queue_(options.laser_queue_capacity),
      odometry_queue_(options.odometry_queue_capacity),
      laser_(options.laser_channel, InputTypeName(options.laser_type), options),
      odometry_(options.odometry_channel, InputTypeName(options.odometry_type), options) {}

LcmInput::~LcmInput() { Stop(); }

bool LcmInput::Start(std::string* error) {
  if (thread_.joinable()) return true;
  if (options_.laser_enabled) laser_.Connecting();
  odometry_.Connecting();
  if (!lcm_) lcm_ = std::make_unique<lcm::LCM>(options_.url);
  if (!lcm_->good()) {
    *error = "cannot open LCM at lcm.url = \"" + options_.url + "\" for input.source = \"lcm\"";
    if (options_.laser_enabled) laser_.Failed(*error);
    odometry_.Failed(*error);
    return false;
  }
  const Time now = Now();
  if (options_.laser_enabled) {
    lcm_->subscribe(options_.laser_channel, &LcmInput::OnLaser, this);
    laser_.Subscribed(now);
  }
  lcm_->subscribe(options_.odometry_channel, &LcmInput::OnOdometry, this);
  odometry_.Subscribed(now);
  stop_.store(false, std::memory_order_release);
  thread_ = std::thread([this] {
    // Nothing a message holds throws; what is left (out of memory) stops the input, said in
    // its health, instead of terminating atlasd.
    try {
      Run();
    } catch (const std::exception& e) {
      const std::string why = std::string("the LCM input stopped: ") + e.what();
      if (options_.laser_enabled) laser_.Failed(why, DriverState::kFailed);
      odometry_.Failed(why, DriverState::kFailed);
    }
  });
  return true;
}

void LcmInput::Stop() {
  stop_.store(true, std::memory_order_release);
  if (!thread_.joinable()) return;
  thread_.join();
  if (options_.laser_enabled) laser_.Stopped();
  odometry_.Stopped();
}

void LcmInput::Run() {
  if (options_.realtime_priority > 0) {
    if (const std::string why = UseRealtimePriority(options_.realtime_priority); !why.empty())
      odometry_.Failed(why + ": the LCM input runs normally");
  }
  while (!stop_.load(std::memory_order_acquire)) {
    // Short waits keep Stop() prompt and the silences checked.
    if (lcm_->handleTimeout(50) < 0) {
      const std::string e = "LCM handle failed on lcm.url = \"" + options_.url + "\"; retrying";
      if (options_.laser_enabled) laser_.Failed(e);
      odometry_.Failed(e);
      std::this_thread::sleep_for(std::chrono::milliseconds(100));
    }
    const Time now = Now();
    if (options_.laser_enabled) laser_.CheckSilence(now);
    odometry_.CheckSilence(now);
  }
}

namespace {

Time ArrivalOf(const lcm::ReceiveBuffer& buffer) {
  const int64_t realtime_now_us = std::chrono::duration_cast<std::chrono::microseconds>(
                                      std::chrono::system_clock::now().time_since_epoch())
                                      .count();
  return ArrivalOnMonotonicClock(buffer.recv_utime, realtime_now_us, Now());
}

}  // namespace

void LcmInput::OnLaser(const lcm::ReceiveBuffer* buffer, const std::string&) {
  const Time arrival = ArrivalOf(*buffer);
  const std::span<const uint8_t> bytes(static_cast<const uint8_t*>(buffer->data),
                                       buffer->data_size);
  Decoded<LaserScan> d = DecodeLaserMessage(options_.laser_type, bytes, options_.laser, arrival);
  laser_.Received(arrival, bytes.size(), d.error);
  if (!d.sample) return;
  laser_queue_.Push(std::move(*d.sample));
  if (options_.on_scan) options_.on_scan();
}

void LcmInput::OnOdometry(const lcm::ReceiveBuffer* buffer, const std::string&) {
  const Time arrival = ArrivalOf(*buffer);
  const std::span<const uint8_t> bytes(static_cast<const uint8_t*>(buffer->data),
                                       buffer->data_size);
  Decoded<OdometrySample> d = DecodeOdometryMessage(options_.odometry_type, bytes, arrival);
  odometry_.Received(arrival, bytes.size(), d.error);
  if (d.sample) odometry_queue_.Push(*d.sample);
}

}  // namespace atlas
