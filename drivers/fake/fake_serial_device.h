#pragma once
// The common part of the fake serial devices (fake_lms, fake_p2os): a pseudo-terminal whose
// slave path (or a symlink to it) the driver opens, a thread that answers the host's bytes and
// sends the device's messages when the playback clock says they are due, and the fault
// injection of FaultOptions applied to every outgoing message:
//   garbage     bytes before the message;          corrupt   last CRC/checksum byte flipped;
//   truncate    only the first half is sent;       stall     nothing sent (the device still
//                                                            hears the host, answers nothing);
//   drop        the pty is closed (the driver reads EIO), then recreated at the same path and
//               the device powers up again (OnPowerUp).

#include <atomic>
#include <cstdint>
#include <memory>
#include <mutex>
#include <span>
#include <string>
#include <thread>
#include <vector>

#include "drivers/fake/fault_options.h"
#include "drivers/fake/playback.h"
#include "drivers/serial/pseudo_terminal.h"

namespace atlas::fake {

class FakeSerialDevice {
 public:
  FakeSerialDevice(std::string name, std::string link, FaultOptions faults,
                   std::shared_ptr<const PlaybackClock> clock);
  virtual ~FakeSerialDevice();
  FakeSerialDevice(const FakeSerialDevice&) = delete;
  FakeSerialDevice& operator=(const FakeSerialDevice&) = delete;

  // Creates the pseudo-terminal (and link). Call before Start().
  bool Open(std::string* error);
  void Start();
  void Stop();  // joins; subclasses' destructors must call it

  // The path a driver opens (the link if given, else /dev/pts/N). Stable across drops only
  // when there is a link.
  std::string path() const;
  const FaultCounts& fault_counts() const { return counts_; }
  uint64_t messages_sent() const { return messages_sent_.load(std::memory_order_relaxed); }
  // True once the recording has been played to its end.
  bool finished() const { return finished_.load(std::memory_order_acquire); }
  const std::string& name() const { return name_; }

 protected:
  // The device is (re)powered: reset its protocol state.
  virtual void OnPowerUp() = 0;
  // Bytes the host wrote (also while stalled: replies are then suppressed).
  virtual void OnHostBytes(std::span<const uint8_t> bytes, Time now) = 0;
  // Sends what is due at `now` (SendMessage); returns when to be called next.
  virtual Time Tick(Time now) = 0;

  // A reply to the host: sent as is (dropped while stalled).
  bool SendReply(const std::vector<uint8_t>& bytes);
  // A device message, with the configured faults. Returns true if it went out intact. A full
  // pty (driver not reading) holds the device up to 1 s, so that a slow reader on a loaded
  // machine loses nothing; after that the message is dropped.
  bool SendMessage(std::vector<uint8_t> bytes);
  bool Stalled(Time now) const;
  int SlaveBaud() const { return pty_.SlaveBaud(); }
  void SetFinished() { finished_.store(true, std::memory_order_release); }
  const PlaybackClock& clock() const { return *clock_; }

 private:
  void Loop();
  bool SleepInterruptible(Duration d);

  std::string name_;
  std::string link_;
  FaultOptions faults_;
  std::shared_ptr<const PlaybackClock> clock_;
  PseudoTerminal pty_;
  mutable std::mutex path_mutex_;
  std::string path_;
  std::thread thread_;
  std::atomic<bool> stop_{false};
  std::atomic<bool> finished_{false};
  std::atomic<uint64_t> messages_sent_{0};
  FaultCounts counts_;
  uint64_t message_index_ = 0;
  bool dropped_ = false;
  bool stall_counted_ = false;
};

}  // namespace atlas::fake
