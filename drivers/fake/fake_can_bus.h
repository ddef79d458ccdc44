#pragma once
// The device side of the fake CAN bus (docs/devices.md, "SocketCAN and the fake bus"):
// listens on a Unix SOCK_SEQPACKET socket at PATH, accepts any number of clients (atlasd
// connects as "unix:PATH"), and sends every frame to all of them as one 16-byte
// struct can_frame per datagram. Clients that went away are forgotten. Not thread-safe: one
// thread (the fake base) drives it.

#include <cstdint>
#include <string>
#include <vector>

#include "drivers/can/can_frame.h"

namespace atlas::fake {

class FakeCanBus {
 public:
  FakeCanBus() = default;
  ~FakeCanBus();
  FakeCanBus(const FakeCanBus&) = delete;
  FakeCanBus& operator=(const FakeCanBus&) = delete;

  // Binds and listens at `path` (an old socket file there is removed).
  bool Listen(const std::string& path, std::string* error);
  // Closes the listener and every client, removes the socket file: the peer sees EOF.
  void Close();
  bool is_listening() const { return listener_ >= 0; }
  const std::string& path() const { return path_; }

  // Accepts clients waiting to connect (non-blocking); returns how many are connected.
  size_t AcceptPending();
  size_t clients() const { return clients_.size(); }
  // Sends one frame to every client; returns how many got it.
  size_t Broadcast(const CanFrame& frame);
  // Sends raw bytes as one datagram (fault injection: a datagram that is not a can_frame).
  size_t BroadcastRaw(const void* data, size_t len);

 private:
  int listener_ = -1;
  std::string path_;
  std::vector<int> clients_;
};

}  // namespace atlas::fake
