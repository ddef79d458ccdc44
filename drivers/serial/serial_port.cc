#include "drivers/serial/serial_port.h"

#include <errno.h>
#include <fcntl.h>
#include <poll.h>
#include <string.h>
#include <sys/file.h>
#include <sys/ioctl.h>
#include <termios.h>
#include <unistd.h>

#include <chrono>
#include <utility>

namespace atlas {
namespace {

struct BaudCode {
  int baud;
  speed_t code;
};
constexpr BaudCode kBauds[] = {
    {1200, B1200},   {2400, B2400},   {4800, B4800},     {9600, B9600},     {19200, B19200},
    {38400, B38400}, {57600, B57600}, {115200, B115200}, {230400, B230400}, {500000, B500000}};

bool IsGoneErrno(int err) { return err == EIO || err == ENXIO || err == ENODEV || err == EBADF; }

std::string ErrnoText(const std::string& device, int err) { return SerialErrnoText(device, err); }

}  // namespace

std::string SerialErrnoText(const std::string& device, int err) {
  std::string what = "serial " + device + ": ";
  switch (err) {
    case ENOENT:
      return what + "no such device (ENOENT): is it plugged in, is the path right?";
    case EACCES:
    case EPERM:
      return what + "permission denied (" + (err == EACCES ? "EACCES" : "EPERM") +
             "): add the user to the dialout group (sudo usermod -aG dialout $USER, then log in "
             "again)";
    case EBUSY:
    case EWOULDBLOCK:
      return what + "device busy (" + (err == EBUSY ? "EBUSY" : "EWOULDBLOCK") +
             "): another process holds it open exclusively; stop it first";
    case ENOTTY:
      return what + "not a terminal (ENOTTY): the path is not a serial device";
    default:
      return what + strerror(err) + " (errno " + std::to_string(err) + ")";
  }
}

bool IsSupportedBaud(int baud) {
  for (const auto& b : kBauds)
    if (b.baud == baud) return true;
  return false;
}

std::string SerialOptions::Validate() const {
  if (device.empty()) return "serial: device path is empty";
  if (!IsSupportedBaud(baud))
    return "serial " + device + ": unsupported baud rate " + std::to_string(baud) +
           " (use 1200..230400 or 500000)";
  return "";
}

bool ConfigureRawTerminal(int fd, int baud, std::string* error) {
  speed_t code = 0;
  for (const auto& b : kBauds)
    if (b.baud == baud) code = b.code;
  if (code == 0) {
    *error = "unsupported baud rate " + std::to_string(baud);
    return false;
  }
  termios tio{};
  if (tcgetattr(fd, &tio) != 0) {
    *error = std::string("tcgetattr: ") + strerror(errno);
    return false;
  }
  cfmakeraw(&tio);
  tio.c_cflag &= ~(CSTOPB | PARENB | CRTSCTS | CSIZE);
  tio.c_cflag |= CS8 | CLOCAL | CREAD;
  tio.c_iflag &= ~(IXON | IXOFF | IXANY);
  tio.c_cc[VMIN] = 0;
  tio.c_cc[VTIME] = 0;
  cfsetispeed(&tio, code);
  cfsetospeed(&tio, code);
  if (tcsetattr(fd, TCSANOW, &tio) != 0) {
    *error = std::string("tcsetattr: ") + strerror(errno);
    return false;
  }
  return true;
}

int TerminalBaud(int fd) {
  termios tio{};
  if (tcgetattr(fd, &tio) != 0) return 0;
  const speed_t code = cfgetospeed(&tio);
  for (const auto& b : kBauds)
    if (b.code == code) return b.baud;
  return 0;
}

SerialPort::~SerialPort() { Close(); }

SerialPort::SerialPort(SerialPort&& other) noexcept
    : fd_(std::exchange(other.fd_, -1)), options_(std::move(other.options_)) {}

SerialPort& SerialPort::operator=(SerialPort&& other) noexcept {
  if (this != &other) {
    Close();
    fd_ = std::exchange(other.fd_, -1);
    options_ = std::move(other.options_);
  }
  return *this;
}

bool SerialPort::Open(const SerialOptions& options, std::string* error) {
  Close();
  if (std::string v = options.Validate(); !v.empty()) {
    *error = v;
    return false;
  }
  options_ = options;
  const int fd = ::open(options.device.c_str(), O_RDWR | O_NOCTTY | O_NONBLOCK | O_CLOEXEC);
  if (fd < 0) {
    *error = ErrnoText(options.device, errno);
    return false;
  }
  if (!isatty(fd)) {
    ::close(fd);
    *error = ErrnoText(options.device, ENOTTY);
    return false;
  }
  if (options.exclusive) {
    if (flock(fd, LOCK_EX | LOCK_NB) != 0 || ioctl(fd, TIOCEXCL) != 0) {
      const int err = errno;
      ::close(fd);
      *error = ErrnoText(options.device, err);
      return false;
    }
  }
  // Bytes received before the line is at our rate are stale (or line noise): drop them, then
  // set the rate, so that nothing sent at the new rate is lost.
  tcflush(fd, TCIOFLUSH);
  std::string why;
  if (!ConfigureRawTerminal(fd, options.baud, &why)) {
    ::close(fd);
    *error = "serial " + options.device + ": " + why;
    return false;
  }
  fd_ = fd;
  return true;
}

bool SerialPort::Reopen(int baud, std::string* error) {
  SerialOptions o = options_;
  o.baud = baud;
  Close();
  return Open(o, error);
}

void SerialPort::Close() {
  if (fd_ >= 0) {
    if (options_.exclusive) {
      ioctl(fd_, TIOCNXCL);
      flock(fd_, LOCK_UN);
    }
    ::close(fd_);
    fd_ = -1;
  }
}

SerialResult SerialPort::Read(uint8_t* buf, size_t cap, int timeout_ms) {
  SerialResult r;
  if (fd_ < 0) {
    r.status = SerialIo::kError;
    r.error = "serial " + options_.device + ": not open";
    return r;
  }
  // A signal (EINTR) or a wake-up with nothing to read (EAGAIN) is not the timeout: wait out
  // the rest of it, so that a caller's "no byte for timeout_ms" really means that.
  const auto deadline = std::chrono::steady_clock::now() + std::chrono::milliseconds(timeout_ms);
  for (int wait_ms = timeout_ms;;) {
    pollfd p{fd_, POLLIN, 0};
    const int k = ::poll(&p, 1, wait_ms);
    if (k < 0 && errno != EINTR) {
      r.status = SerialIo::kError;
      r.error = ErrnoText(options_.device, errno);
      return r;
    }
    if (k > 0 && (p.revents & (POLLIN | POLLHUP | POLLERR))) {
      const ssize_t n = ::read(fd_, buf, cap);
      if (n > 0) {
        r.status = SerialIo::kData;
        r.n = static_cast<size_t>(n);
        return r;
      }
      if (n == 0 || IsGoneErrno(errno)) {
        r.status = SerialIo::kGone;
        r.error = "serial " + options_.device + ": device went away (" +
                  (n == 0 ? std::string("EOF") : std::string(strerror(errno))) + ")";
        return r;
      }
      if (errno != EAGAIN && errno != EINTR) {
        r.status = SerialIo::kError;
        r.error = ErrnoText(options_.device, errno);
        return r;
      }
    } else if (k > 0 && (p.revents & POLLNVAL)) {
      r.status = SerialIo::kGone;
      r.error = "serial " + options_.device + ": descriptor invalid";
      return r;
    }
    if (k == 0 || timeout_ms <= 0) return r;  // timed out (or only polled)
    const auto left = std::chrono::duration_cast<std::chrono::milliseconds>(
        deadline - std::chrono::steady_clock::now());
    if (left.count() <= 0) return r;
    wait_ms = static_cast<int>(left.count());
  }
}

SerialResult SerialPort::WriteAll(const uint8_t* data, size_t len, int timeout_ms) {
  SerialResult r;
  size_t done = 0;
  int waited_ms = 0;
  while (done < len) {
    const ssize_t n = ::write(fd_, data + done, len - done);
    if (n > 0) {
      done += static_cast<size_t>(n);
      continue;
    }
    if (n < 0 && (errno == EAGAIN || errno == EINTR)) {
      if (waited_ms >= timeout_ms) {
        r.status = SerialIo::kTimeout;
        r.n = done;
        r.error = "serial " + options_.device + ": write timed out";
        return r;
      }
      pollfd p{fd_, POLLOUT, 0};
      ::poll(&p, 1, 10);
      waited_ms += 10;
      continue;
    }
    r.status = (n == 0 || IsGoneErrno(errno)) ? SerialIo::kGone : SerialIo::kError;
    r.n = done;
    r.error = ErrnoText(options_.device, n == 0 ? EIO : errno);
    return r;
  }
  r.status = SerialIo::kData;
  r.n = done;
  return r;
}

void SerialPort::FlushInput() {
  if (fd_ >= 0) tcflush(fd_, TCIFLUSH);
}

}  // namespace atlas
