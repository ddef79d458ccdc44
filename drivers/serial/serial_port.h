#pragma once
// A serial line owned through termios: raw mode, 8N1, no flow control, one of the standard
// rates or 500000 (the SICK LMS 2xx top rate, devices.md section 1). The port is opened
// exclusively (TIOCEXCL, plus an advisory flock so that a second atlasd is refused even when
// running as root), read with poll() and a timeout, and a rate change is a reopen (as the LMS
// start-up sequence prescribes). Every error names the device and the errno in plain words.
//
// This file owns a file descriptor; it knows nothing of any protocol.

#include <cstddef>
#include <cstdint>
#include <string>

namespace atlas {

// The plain-words error for errno `err` on `device`: names both, and says what to do
// (ENOENT: plugged in?; EACCES: the dialout group; EBUSY: another process holds it).
std::string SerialErrnoText(const std::string& device, int err);

// True for the rates this port accepts: 1200 ... 230400 and 500000.
bool IsSupportedBaud(int baud);

struct SerialOptions {
  std::string device;  // e.g. /dev/ttyUSB0 or a pseudo-terminal path
  int baud = 9600;
  bool exclusive = true;
  std::string Validate() const;  // empty when valid
};

enum class SerialIo {
  kData,     // n > 0 bytes read or written
  kTimeout,  // nothing within the timeout
  kGone,     // EOF, EIO, hang-up: the device went away; close and reopen
  kError,    // any other failure (see error)
};

struct SerialResult {
  SerialIo status = SerialIo::kTimeout;
  size_t n = 0;
  std::string error;
};

class SerialPort {
 public:
  SerialPort() = default;
  ~SerialPort();
  SerialPort(const SerialPort&) = delete;
  SerialPort& operator=(const SerialPort&) = delete;
  SerialPort(SerialPort&& other) noexcept;
  SerialPort& operator=(SerialPort&& other) noexcept;

  // Opens and configures the line. On failure returns false and sets *error, e.g.
  // "serial /dev/ttyUSB0: permission denied (EACCES): add the user to the dialout group".
  bool Open(const SerialOptions& options, std::string* error);
  // Closes and opens the same device at another rate.
  bool Reopen(int baud, std::string* error);
  void Close();
  bool is_open() const { return fd_ >= 0; }
  int fd() const { return fd_; }
  int baud() const { return options_.baud; }
  const std::string& device() const { return options_.device; }

  // Waits up to timeout_ms for bytes, then reads what is there (at most cap).
  SerialResult Read(uint8_t* buf, size_t cap, int timeout_ms);
  // Writes all bytes or fails; waits up to timeout_ms in total for the line to accept them.
  SerialResult WriteAll(const uint8_t* data, size_t len, int timeout_ms);
  // Discards bytes received but not read.
  void FlushInput();

 private:
  int fd_ = -1;
  SerialOptions options_;
};

// Puts an open terminal into raw 8N1 at `baud`. Returns false and sets *error on failure.
// Shared with the fake devices, which put their side of a pseudo-terminal in raw mode too.
bool ConfigureRawTerminal(int fd, int baud, std::string* error);
// The rate currently set on a terminal, or 0 if unknown.
int TerminalBaud(int fd);

}  // namespace atlas
