#pragma once
// A pseudo-terminal pair (posix_openpt, grantpt, unlockpt, ptsname) standing in for a serial
// cable: the fake device owns the master side, a driver opens the slave path (or a symlink to
// it) exactly as it would open /dev/ttyUSB0.
//
// The master keeps one descriptor of the slave open itself, so that the master never sees a
// hang-up while a driver closes and reopens the line (the LMS baud switch is a reopen). The
// slave starts in raw mode so that nothing is echoed back. The rate a driver set on the slave
// is visible through SlaveBaud(): a fake can refuse to answer at a rate it is not "at".

#include <cstddef>
#include <cstdint>
#include <string>

namespace atlas {

class PseudoTerminal {
 public:
  PseudoTerminal() = default;
  ~PseudoTerminal();
  PseudoTerminal(const PseudoTerminal&) = delete;
  PseudoTerminal& operator=(const PseudoTerminal&) = delete;

  // Creates the pair; if `link` is not empty, (re)points a symlink at the slave path.
  bool Create(const std::string& link, std::string* error);
  // Closes the master (a driver reading the slave sees EIO/hang-up) and removes the symlink.
  void Close();
  bool is_open() const { return master_ >= 0; }

  int master_fd() const { return master_; }
  const std::string& slave_path() const { return slave_path_; }
  // The path a driver should open: the link if there is one, else the slave path.
  const std::string& path() const { return link_.empty() ? slave_path_ : link_; }
  int SlaveBaud() const;

  // Master side I/O, non-blocking. Write returns false if the pair is gone.
  bool WriteAll(const uint8_t* data, size_t len, int timeout_ms = 1000);
  // Reads what is there within timeout_ms; returns bytes read (0 on timeout), -1 on failure.
  long Read(uint8_t* buf, size_t cap, int timeout_ms);

 private:
  int master_ = -1;
  int slave_hold_ = -1;
  std::string slave_path_;
  std::string link_;
};

}  // namespace atlas
