#pragma once
// The AgileX odometry reader thread (docs/devices.md, section 2): frames from a
// CanTransport (SocketCAN "can0" or the fake bus "unix:PATH"), decoded by drivers/agilex,
// 0x311 wheel distances integrated by WheelOdometryIntegrator (discontinuities skipped and
// counted), each integrated step pushed as an OdometrySample stamped at arrival (the kernel's
// SO_TIMESTAMP on SocketCAN, SO_TIMESTAMPNS on the fake bus). 0x211 system state and CAN error
// frames are reported in the health, never fatal. ENETDOWN (interface down) is reported and the
// socket kept, as candump does; a closed bus or a removed interface ends the session, and the
// transport is reopened with capped backoff (growing while sessions bring no frame). The pose goes
// on where it was across a reconnect, but the counters are re-referenced on every (re)connect and
// after a gap longer than odometry.max_gap_s: a base reboot (counters reset, seconds of silence) is
// one discontinuity, never a jump.

#include <memory>
#include <string>

#include "core/common/sensor_types.h"
#include "drivers/agilex/agilex_messages.h"
#include "drivers/agilex/wheel_odometry.h"
#include "drivers/can/can_transport.h"
#include "drivers/device/device_reader.h"
#include "drivers/queue/spsc_queue.h"

namespace atlas {

struct OdometryReaderOptions {
  std::string interface_name = "can0";  // or "unix:PATH"
  agilex::WheelOdometryOptions odometry;
  size_t queue_capacity = 256;
  ReconnectOptions reconnect;
  std::string Validate() const;
};

class OdometryReader final : public DeviceReader {
 public:
  explicit OdometryReader(const OdometryReaderOptions& options);  // options must be valid
  ~OdometryReader() override;

  bool Pop(OdometrySample* sample) { return queue_.Pop(sample); }
  SpscQueue<OdometrySample>& queue() { return queue_; }

 protected:
  bool Connect(std::string* error) override;
  SessionEnd ReadUntilGone(std::string* error) override;
  void Disconnect() override;
  uint64_t QueueDrops() const override { return queue_.Dropped(); }

 private:
  void HandleFrame(const CanReadResult& r);

  OdometryReaderOptions options_;
  std::unique_ptr<CanTransport> transport_;
  agilex::WheelOdometryIntegrator integrator_;
  SpscQueue<OdometrySample> queue_;
  agilex::MotionState motion_{};  // the base's last reported velocities
  agilex::SystemState last_system_{};
  bool have_system_ = false;
};

}  // namespace atlas
