#include "drivers/device/odometry_reader.h"

#include <cstdio>

namespace atlas {

std::string OdometryReaderOptions::Validate() const {
  if (interface_name.empty()) return "odometry: CAN interface name is empty";
  if (interface_name.rfind("unix:", 0) == 0 && interface_name.size() == 5)
    return "odometry: unix: needs a socket path (unix:/run/atlas/can)";
  if (std::string e = odometry.Validate(); !e.empty()) return "odometry: " + e;
  if (queue_capacity == 0) return "odometry: queue_capacity must be > 0";
  return reconnect.Validate();
}

OdometryReader::OdometryReader(const OdometryReaderOptions& options)
    : DeviceReader("odometry " + options.interface_name, options.reconnect),
      options_(options),
      transport_(MakeCanTransport(options.interface_name)),
      integrator_(options.odometry),
      queue_(options.queue_capacity) {}

OdometryReader::~OdometryReader() { Stop(); }

bool OdometryReader::Connect(std::string* error) {
  if (!transport_->Open(error)) return false;
  // Whatever the base did meanwhile (a reboot resets its counters), the counters of the last
  // session are no reference for this one.
  integrator_.Rereference();
  return true;
}

void OdometryReader::Disconnect() { transport_->Close(); }

void OdometryReader::HandleFrame(const CanReadResult& r) {
  health_.bytes.fetch_add(r.frame.dlc, std::memory_order_relaxed);
  const agilex::Message m = agilex::DecodeFrame(r.frame);
  switch (m.kind) {
    case agilex::FrameKind::kOdometry: {
      health_.CountMessage(r.stamp);
      const agilex::OdometryStep step = integrator_.Update(r.stamp, m.odometry);
      if (step == agilex::OdometryStep::kDiscontinuity ||
          step == agilex::OdometryStep::kRereferenced) {
        health_.discontinuities.fetch_add(1, std::memory_order_relaxed);
        health_.SetError(std::string("odometry step skipped (") +
                         agilex::ToString(integrator_.last_cause()) + ", counters left " +
                         std::to_string(m.odometry.left_mm) + " mm, right " +
                         std::to_string(m.odometry.right_mm) + " mm): re-referenced");
        // An implausible frame is skipped; a new reference is a sample at the kept pose, as
        // the first one is.
        if (step == agilex::OdometryStep::kDiscontinuity) return;
      }
      OdometrySample sample = integrator_.sample();
      sample.linear_velocity = motion_.linear_mps();
      sample.angular_velocity = motion_.angular_radps();
      queue_.Push(sample);
      health_.samples.fetch_add(1, std::memory_order_relaxed);
      return;
    }
    case agilex::FrameKind::kSystemState:
      if (!have_system_ || !(m.system == last_system_)) {
        char b[96];
        std::snprintf(b, sizeof(b), "base state %u, mode %u, battery %.1f V, faults 0x%02X",
                      m.system.vehicle_state, m.system.control_mode, m.system.battery_volts(),
                      m.system.fault_bits);
        health_.SetDeviceStatus(b);
        // Said when the state, mode or faults change (not the battery voltage).
        if (!have_system_ || m.system.vehicle_state != last_system_.vehicle_state ||
            m.system.control_mode != last_system_.control_mode ||
            m.system.fault_bits != last_system_.fault_bits)
          ReportCondition(m.system.fault_bits != 0 || m.system.vehicle_state != 0
                              ? LogPriority::kWarning
                              : LogPriority::kInfo,
                          b);
        last_system_ = m.system;
        have_system_ = true;
      }
      return;
    case agilex::FrameKind::kMotionState:
      motion_ = m.motion;
      return;
    case agilex::FrameKind::kUnknownId:
      return;
    case agilex::FrameKind::kErrorFrame: {
      health_.error_frames.fetch_add(1, std::memory_order_relaxed);
      char b[64];
      std::snprintf(b, sizeof(b), "CAN error frame, class 0x%08X", r.frame.id & kCanEffMask);
      health_.SetError(b);
      return;
    }
    case agilex::FrameKind::kBadLength:
    case agilex::FrameKind::kNotStandardData:
      health_.bad_messages.fetch_add(1, std::memory_order_relaxed);
      return;
  }
}

DeviceReader::SessionEnd OdometryReader::ReadUntilGone(std::string* error) {
  while (!Stopping()) {
    const CanReadResult r = transport_->Read(50);
    const Time now = Now();
    switch (r.status) {
      case CanRead::kFrame:
        HandleFrame(r);
        break;
      case CanRead::kBadFrame:
        health_.bad_messages.fetch_add(1, std::memory_order_relaxed);
        health_.SetError(r.error);
        break;
      case CanRead::kNetDown:
        // The socket stays bound to the interface: frames come again once it is up. Said in
        // the health; the silence rule below still reopens after reopen_after_silence, with
        // a backoff that grows while no frame comes (DeviceReader).
        health_.SetError(r.error + "; waiting for it to come up");
        ReportCondition(LogPriority::kWarning, r.error + "; waiting for it to come up");
        break;
      case CanRead::kGone:
      case CanRead::kError:
        *error = r.error;
        return SessionEnd::kGone;
      case CanRead::kTimeout:
        break;
    }
    if (TrackSilence(r.status == CanRead::kFrame, now)) {
      *error = "odometry " + options_.interface_name + ": no frame for " +
               std::to_string(ToSeconds(reconnect_.reopen_after_silence)).substr(0, 4) +
               " s; reopening";
      return SessionEnd::kGone;
    }
  }
  return SessionEnd::kStopped;
}

}  // namespace atlas
