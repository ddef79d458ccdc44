#pragma once
// The priorities of a log line, numbered as syslog and sd-daemon(3) number them (sd-daemon.h:
// SD_ERR "<3>" .. SD_DEBUG "<7>"), so that a line written to stderr under systemd with that
// prefix is filed at that priority and `journalctl -p warning` shows errors and warnings only.

namespace atlas {

enum class LogPriority : int {
  kErr = 3,      // something does not work: a device cannot be used, the loop stopped
  kWarning = 4,  // working, degraded: a device lost or silent, a setting refused
  kNotice = 5,   // a normal but significant change: a device running (again)
  kInfo = 6,     // progress: connecting, stopped
  kDebug = 7,
};

}  // namespace atlas
