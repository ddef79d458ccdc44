#include "drivers/can/can_transport.h"

#include <errno.h>
#include <fcntl.h>
#include <linux/can.h>
#include <linux/can/error.h>
#include <linux/can/raw.h>
#include <net/if.h>
#include <poll.h>
#include <string.h>
#include <sys/ioctl.h>
#include <sys/socket.h>
#include <sys/time.h>
#include <sys/un.h>
#include <time.h>
#include <unistd.h>

#include <utility>

#include "drivers/can/can_frame_linux.h"

namespace atlas {

std::string CanErrnoText(const std::string& name, int err) {
  const std::string what = "CAN " + name + ": ";
  switch (err) {
    case EAFNOSUPPORT:
      return what +
             "this kernel has no CAN support (EAFNOSUPPORT): load the modules (modprobe can "
             "can_raw) or use the fake bus, unix:PATH";
    case ENODEV:
      return what + "no such interface (ENODEV): check the name (ip link show type can)";
    case ENETDOWN:
      return what + "interface is down (ENETDOWN): bring it up (ip link set " + name +
             " up type can bitrate 500000)";
    case ENOENT:
    case ECONNREFUSED:
      return what + "nobody is listening (" + (err == ENOENT ? "ENOENT" : "ECONNREFUSED") +
             "): start the fake device (atlas-fakedev --can-socket " +
             (name.starts_with("unix:") ? name.substr(5) : name) + ")";
    case EACCES:
      return what + "permission denied (EACCES)";
    default:
      return what + strerror(err) + " (errno " + std::to_string(err) + ")";
  }
}

CanRead CanReadStatusForErrno(int err) {
  switch (err) {
    case ENETDOWN:
      return CanRead::kNetDown;
    case ENODEV:
    case ENXIO:
      return CanRead::kGone;
    default:
      return CanRead::kError;
  }
}

namespace {

// Waits for input on fd; returns 1 ready, 0 timeout, -1 error (errno set).
int WaitReadable(int fd, int timeout_ms) {
  pollfd p{fd, POLLIN, 0};
  const int k = ::poll(&p, 1, timeout_ms);
  if (k < 0 && errno == EINTR) return 0;
  return k;
}

// The kernel's receive stamp in `msg` (SCM_TIMESTAMP or SCM_TIMESTAMPNS, both CLOCK_REALTIME)
// carried over to the monotonic clock by its age: `arrival` (Now() right after the receive)
// minus how long ago the kernel stamped. False when there is none or it is implausible (more
// than a second old, or in the future: the real-time clock was stepped).
bool KernelArrival(msghdr& msg, Time arrival, Time* stamp) {
  for (cmsghdr* c = CMSG_FIRSTHDR(&msg); c != nullptr; c = CMSG_NXTHDR(&msg, c)) {
    if (c->cmsg_level != SOL_SOCKET) continue;
    int64_t sec = 0, nsec = 0;
    if (c->cmsg_type == SCM_TIMESTAMP) {
      timeval tv;
      memcpy(&tv, CMSG_DATA(c), sizeof(tv));
      sec = tv.tv_sec;
      nsec = static_cast<int64_t>(tv.tv_usec) * 1000;
    } else if (c->cmsg_type == SCM_TIMESTAMPNS) {
      timespec ts;
      memcpy(&ts, CMSG_DATA(c), sizeof(ts));
      sec = ts.tv_sec;
      nsec = ts.tv_nsec;
    } else {
      continue;
    }
    timespec now_rt;
    clock_gettime(CLOCK_REALTIME, &now_rt);
    const int64_t age_ns = (now_rt.tv_sec - sec) * 1000000000LL + (now_rt.tv_nsec - nsec);
    if (age_ns < 0 || age_ns >= 1000000000LL) return false;
    *stamp = arrival - Duration(age_ns);
    return true;
  }
  return false;
}

class SocketCanTransport final : public CanTransport {
 public:
  explicit SocketCanTransport(std::string name) : name_(std::move(name)) {}
  ~SocketCanTransport() override { Close(); }

  bool Open(std::string* error) override {
    Close();
    const int fd = ::socket(PF_CAN, SOCK_RAW | SOCK_NONBLOCK | SOCK_CLOEXEC, CAN_RAW);
    if (fd < 0) return Fail(errno, error);
    ifreq ifr{};
    if (name_.size() >= sizeof(ifr.ifr_name)) {
      ::close(fd);
      return Fail(ENODEV, error);
    }
    strncpy(ifr.ifr_name, name_.c_str(), sizeof(ifr.ifr_name) - 1);
    if (ioctl(fd, SIOCGIFINDEX, &ifr) != 0) {
      const int err = errno;
      ::close(fd);
      return Fail(err, error);
    }
    std::vector<can_filter> filters;
    for (uint32_t id : AgilexFilterIds()) filters.push_back({id, CAN_SFF_MASK | CAN_EFF_FLAG});
    const can_err_mask_t err_mask = CAN_ERR_MASK;
    const int on = 1;
    if (setsockopt(fd, SOL_CAN_RAW, CAN_RAW_FILTER, filters.data(),
                   static_cast<socklen_t>(filters.size() * sizeof(can_filter))) != 0 ||
        setsockopt(fd, SOL_CAN_RAW, CAN_RAW_ERR_FILTER, &err_mask, sizeof(err_mask)) != 0 ||
        setsockopt(fd, SOL_SOCKET, SO_TIMESTAMP, &on, sizeof(on)) != 0) {
      const int err = errno;
      ::close(fd);
      return Fail(err, error);
    }
    sockaddr_can addr{};
    addr.can_family = AF_CAN;
    addr.can_ifindex = ifr.ifr_ifindex;
    if (bind(fd, reinterpret_cast<sockaddr*>(&addr), sizeof(addr)) != 0) {
      const int err = errno;
      ::close(fd);
      return Fail(err, error);
    }
    fd_ = fd;
    return true;
  }

  void Close() override {
    if (fd_ >= 0) ::close(fd_);
    fd_ = -1;
  }
  bool is_open() const override { return fd_ >= 0; }
  const std::string& name() const override { return name_; }

  CanReadResult Read(int timeout_ms) override {
    CanReadResult r;
    const int k = WaitReadable(fd_, timeout_ms);
    if (k == 0) return r;
    struct can_frame raw;
    char control[CMSG_SPACE(sizeof(timeval))];
    iovec iov{&raw, sizeof(raw)};
    msghdr msg{};
    msg.msg_iov = &iov;
    msg.msg_iovlen = 1;
    msg.msg_control = control;
    msg.msg_controllen = sizeof(control);
    const ssize_t n = k < 0 ? -1 : recvmsg(fd_, &msg, 0);
    if (n < 0) {
      if (errno == EAGAIN || errno == EINTR) return r;
      r.status = CanReadStatusForErrno(errno);
      r.error = CanErrnoText(name_, errno);
      return r;
    }
    const Time arrival = Now();
    if (n != static_cast<ssize_t>(sizeof(raw))) {
      r.status = CanRead::kBadFrame;
      r.error = "CAN " + name_ + ": short frame of " + std::to_string(n) + " bytes";
      return r;
    }
    r.status = CanRead::kFrame;
    r.frame = FromLinuxCanFrame(raw);
    r.stamp = arrival;
    r.kernel_stamp = KernelArrival(msg, arrival, &r.stamp);
    return r;
  }

  bool Write(const CanFrame& frame, std::string* error) override {
    const struct can_frame raw = ToLinuxCanFrame(frame);
    if (::write(fd_, &raw, sizeof(raw)) != static_cast<ssize_t>(sizeof(raw))) {
      *error = CanErrnoText(name_, errno);
      return false;
    }
    return true;
  }

 private:
  bool Fail(int err, std::string* error) {
    *error = CanErrnoText(name_, err);
    return false;
  }
  std::string name_;
  int fd_ = -1;
};

class FakeBusTransport final : public CanTransport {
 public:
  explicit FakeBusTransport(std::string name) : name_(std::move(name)), path_(name_.substr(5)) {}
  ~FakeBusTransport() override { Close(); }

  bool Open(std::string* error) override {
    Close();
    sockaddr_un addr{};
    addr.sun_family = AF_UNIX;
    if (path_.empty() || path_.size() >= sizeof(addr.sun_path)) {
      *error = "CAN " + name_ + ": the socket path must have 1.." +
               std::to_string(sizeof(addr.sun_path) - 1) + " characters";
      return false;
    }
    memcpy(addr.sun_path, path_.c_str(), path_.size());
    const int fd = ::socket(AF_UNIX, SOCK_SEQPACKET | SOCK_NONBLOCK | SOCK_CLOEXEC, 0);
    if (fd < 0) {
      *error = CanErrnoText(name_, errno);
      return false;
    }
    // Kernel arrival stamps, as on SocketCAN (without them, Now() after the receive).
    const int on = 1;
    (void)setsockopt(fd, SOL_SOCKET, SO_TIMESTAMPNS, &on, sizeof(on));
    if (connect(fd, reinterpret_cast<sockaddr*>(&addr), sizeof(addr)) != 0) {
      const int err = errno;
      ::close(fd);
      *error = CanErrnoText(name_, err);
      return false;
    }
    fd_ = fd;
    return true;
  }
  void Close() override {
    if (fd_ >= 0) ::close(fd_);
    fd_ = -1;
  }
  bool is_open() const override { return fd_ >= 0; }
  const std::string& name() const override { return name_; }

  CanReadResult Read(int timeout_ms) override {
    CanReadResult r;
    const int k = WaitReadable(fd_, timeout_ms);
    if (k == 0) return r;
    uint8_t buf[64];
    char control[CMSG_SPACE(sizeof(timespec))];
    iovec iov{buf, sizeof(buf)};
    msghdr msg{};
    msg.msg_iov = &iov;
    msg.msg_iovlen = 1;
    msg.msg_control = control;
    msg.msg_controllen = sizeof(control);
    const ssize_t n = k < 0 ? -1 : ::recvmsg(fd_, &msg, MSG_TRUNC);
    if (n == 0) {
      r.status = CanRead::kGone;
      r.error = "CAN " + name_ + ": the fake bus closed the connection";
      return r;
    }
    if (n < 0) {
      if (errno == EAGAIN || errno == EINTR) return r;
      r.status = (errno == ECONNRESET || errno == ENOTCONN || errno == EPIPE) ? CanRead::kGone
                                                                              : CanRead::kError;
      r.error = CanErrnoText(name_, errno);
      return r;
    }
    const Time arrival = Now();
    r.stamp = arrival;
    r.kernel_stamp = KernelArrival(msg, arrival, &r.stamp);
    if (n != static_cast<ssize_t>(sizeof(struct can_frame))) {
      r.status = CanRead::kBadFrame;
      r.error = "CAN " + name_ + ": datagram of " + std::to_string(n) +
                " bytes, expected one 16-byte struct can_frame";
      return r;
    }
    struct can_frame raw;
    memcpy(&raw, buf, sizeof(raw));
    r.status = CanRead::kFrame;
    r.frame = FromLinuxCanFrame(raw);
    return r;
  }

  bool Write(const CanFrame& frame, std::string* error) override {
    const struct can_frame raw = ToLinuxCanFrame(frame);
    if (::send(fd_, &raw, sizeof(raw), MSG_NOSIGNAL) != static_cast<ssize_t>(sizeof(raw))) {
      *error = CanErrnoText(name_, errno);
      return false;
    }
    return true;
  }

 private:
  std::string name_;
  std::string path_;
  int fd_ = -1;
};

}  // namespace

std::unique_ptr<CanTransport> MakeCanTransport(const std::string& interface_name) {
  if (interface_name.rfind("unix:", 0) == 0)
    return std::make_unique<FakeBusTransport>(interface_name);
  return std::make_unique<SocketCanTransport>(interface_name);
}

}  // namespace atlas
