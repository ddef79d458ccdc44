#pragma once
// atlasd's log lines on stderr. Under systemd (stderr is the journal: $JOURNAL_STREAM names
// stderr's device and inode, systemd.exec(5)) each line carries the sd-daemon(3) priority
// prefix ("<4>atlasd: ..."), so that journald files it at that priority and
// `journalctl -u atlasd -p warning` shows errors and warnings only. Elsewhere (a terminal, a
// file) the line reads "atlasd: warning: ..." (errors "atlasd: error: ...").

#include <string>
#include <string_view>

#include "core/common/log_priority.h"

namespace atlas {

// The line for `text` (without "atlasd: " and without a newline), newline-terminated.
std::string StderrLogLine(LogPriority priority, std::string_view text, bool journal);

// True when $JOURNAL_STREAM is "<device>:<inode>" of file descriptor 2.
bool StderrIsJournal();

// Writes StderrLogLine(priority, text, StderrIsJournal()) with one write(2), so that lines from
// several threads never interleave. Safe from any thread.
void LogToStderr(LogPriority priority, std::string_view text);

}  // namespace atlas
