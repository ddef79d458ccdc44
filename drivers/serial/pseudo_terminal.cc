#include "drivers/serial/pseudo_terminal.h"

#include <errno.h>
#include <fcntl.h>
#include <poll.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "drivers/serial/serial_port.h"

namespace atlas {

PseudoTerminal::~PseudoTerminal() { Close(); }

bool PseudoTerminal::Create(const std::string& link, std::string* error) {
  Close();
  const int m = posix_openpt(O_RDWR | O_NOCTTY | O_NONBLOCK | O_CLOEXEC);
  if (m < 0) {
    *error = std::string("posix_openpt: ") + strerror(errno);
    return false;
  }
  char name[128];
  if (grantpt(m) != 0 || unlockpt(m) != 0 || ptsname_r(m, name, sizeof(name)) != 0) {
    *error = std::string("pseudo-terminal setup: ") + strerror(errno);
    ::close(m);
    return false;
  }
  const int s = ::open(name, O_RDWR | O_NOCTTY | O_NONBLOCK | O_CLOEXEC);
  if (s < 0) {
    *error = std::string("open ") + name + ": " + strerror(errno);
    ::close(m);
    return false;
  }
  std::string why;
  if (!ConfigureRawTerminal(s, 9600, &why)) {
    *error = std::string(name) + ": " + why;
    ::close(s);
    ::close(m);
    return false;
  }
  if (!link.empty()) {
    ::unlink(link.c_str());
    if (::symlink(name, link.c_str()) != 0) {
      *error = "symlink " + link + " -> " + name + ": " + strerror(errno);
      ::close(s);
      ::close(m);
      return false;
    }
  }
  master_ = m;
  slave_hold_ = s;
  slave_path_ = name;
  link_ = link;
  return true;
}

void PseudoTerminal::Close() {
  if (!link_.empty()) ::unlink(link_.c_str());
  if (slave_hold_ >= 0) ::close(slave_hold_);
  if (master_ >= 0) ::close(master_);
  master_ = slave_hold_ = -1;
}

int PseudoTerminal::SlaveBaud() const { return slave_hold_ >= 0 ? TerminalBaud(slave_hold_) : 0; }

bool PseudoTerminal::WriteAll(const uint8_t* data, size_t len, int timeout_ms) {
  size_t done = 0;
  int waited = 0;
  while (done < len) {
    if (master_ < 0) return false;
    const ssize_t n = ::write(master_, data + done, len - done);
    if (n > 0) {
      done += static_cast<size_t>(n);
    } else if (n < 0 && (errno == EAGAIN || errno == EINTR)) {
      if (waited >= timeout_ms) return false;
      pollfd p{master_, POLLOUT, 0};
      ::poll(&p, 1, 5);
      waited += 5;
    } else {
      return false;
    }
  }
  return true;
}

long PseudoTerminal::Read(uint8_t* buf, size_t cap, int timeout_ms) {
  if (master_ < 0) return -1;
  pollfd p{master_, POLLIN, 0};
  const int k = ::poll(&p, 1, timeout_ms);
  if (k <= 0) return k < 0 && errno != EINTR ? -1 : 0;
  const ssize_t n = ::read(master_, buf, cap);
  if (n > 0) return n;
  if (n < 0 && (errno == EAGAIN || errno == EINTR)) return 0;
  return -1;
}

}  // namespace atlas
