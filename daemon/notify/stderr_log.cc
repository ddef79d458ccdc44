#include "daemon/notify/stderr_log.h"

#include <sys/stat.h>
#include <unistd.h>

#include <cstdio>
#include <cstdlib>

namespace atlas {

std::string StderrLogLine(LogPriority priority, std::string_view text, bool journal) {
  std::string line;
  if (journal) {
    // One digit, 3..7. (Appended, not "<" + std::to_string(): GCC 12 at -O3 warns of a
    // memcpy overlap in that operator+ that cannot happen, -Wrestrict.)
    line += '<';
    line += static_cast<char>('0' + static_cast<int>(priority));
    line += ">atlasd: ";
  } else {
    line = "atlasd: ";
    if (priority == LogPriority::kErr) line += "error: ";
    if (priority == LogPriority::kWarning) line += "warning: ";
  }
  for (char c : text) line += (c == '\n' || c == '\r') ? ' ' : c;  // one line per message
  line += '\n';
  return line;
}

bool StderrIsJournal() {
  const char* stream = std::getenv("JOURNAL_STREAM");
  if (stream == nullptr) return false;
  unsigned long long dev = 0, ino = 0;
  if (std::sscanf(stream, "%llu:%llu", &dev, &ino) != 2) return false;
  struct stat st {};
  if (fstat(STDERR_FILENO, &st) != 0) return false;
  return static_cast<unsigned long long>(st.st_dev) == dev &&
         static_cast<unsigned long long>(st.st_ino) == ino;
}

void LogToStderr(LogPriority priority, std::string_view text) {
  static const bool journal = StderrIsJournal();
  const std::string line = StderrLogLine(priority, text, journal);
  const ssize_t n = write(STDERR_FILENO, line.data(), line.size());
  (void)n;  // nowhere left to report a failed write to stderr
}

}  // namespace atlas
