#include "drivers/fake/fake_can_bus.h"

#include <errno.h>
#include <string.h>
#include <sys/socket.h>
#include <sys/un.h>
#include <unistd.h>

#include "drivers/can/can_frame_linux.h"

namespace atlas::fake {

FakeCanBus::~FakeCanBus() { Close(); }

bool FakeCanBus::Listen(const std::string& path, std::string* error) {
  Close();
  sockaddr_un addr{};
  addr.sun_family = AF_UNIX;
  if (path.empty() || path.size() >= sizeof(addr.sun_path)) {
    *error = "fake CAN bus: socket path must have 1.." + std::to_string(sizeof(addr.sun_path) - 1) +
             " characters: " + path;
    return false;
  }
  memcpy(addr.sun_path, path.c_str(), path.size());
  const int fd = ::socket(AF_UNIX, SOCK_SEQPACKET | SOCK_NONBLOCK | SOCK_CLOEXEC, 0);
  if (fd < 0) {
    *error = std::string("fake CAN bus: socket: ") + strerror(errno);
    return false;
  }
  ::unlink(path.c_str());
  if (bind(fd, reinterpret_cast<sockaddr*>(&addr), sizeof(addr)) != 0 || listen(fd, 8) != 0) {
    *error = "fake CAN bus " + path + ": " + strerror(errno);
    ::close(fd);
    return false;
  }
  listener_ = fd;
  path_ = path;
  return true;
}

void FakeCanBus::Close() {
  for (int c : clients_) ::close(c);
  clients_.clear();
  if (listener_ >= 0) {
    ::close(listener_);
    ::unlink(path_.c_str());
  }
  listener_ = -1;
}

size_t FakeCanBus::AcceptPending() {
  if (listener_ < 0) return 0;
  for (;;) {
    const int c = accept4(listener_, nullptr, nullptr, SOCK_NONBLOCK | SOCK_CLOEXEC);
    if (c < 0) break;
    clients_.push_back(c);
  }
  return clients_.size();
}

size_t FakeCanBus::BroadcastRaw(const void* data, size_t len) {
  size_t sent = 0;
  for (size_t i = 0; i < clients_.size();) {
    const ssize_t n = ::send(clients_[i], data, len, MSG_NOSIGNAL | MSG_DONTWAIT);
    if (n == static_cast<ssize_t>(len)) {
      ++sent;
      ++i;
    } else if (n < 0 && (errno == EAGAIN || errno == EWOULDBLOCK)) {
      ++i;  // a slow client misses this frame, as on a real bus with a full receive queue
    } else {
      ::close(clients_[i]);
      clients_.erase(clients_.begin() + static_cast<long>(i));
    }
  }
  return sent;
}

size_t FakeCanBus::Broadcast(const CanFrame& frame) {
  const struct can_frame raw = ToLinuxCanFrame(frame);
  return BroadcastRaw(&raw, sizeof(raw));
}

}  // namespace atlas::fake
