#pragma once
// What a device driver says in the log, and when: each change of its state once, with the
// reason, never once per retry (docs/atlasd.md, "Logs"). Pure: DriverLog decides the lines,
// DeviceReader hands them to ReconnectOptions::log (atlasd writes them to stderr with the
// sd-daemon priority prefix, so the journal files them by priority).
//
// A session that ends before its first message is a failed attempt like a failed open (as for
// the backoff, see BackoffDelay): a device that opens and dies at once (SocketCAN on a down
// interface) or keeps failing with the same reason is said once, until it delivers again or
// the reason changes.

#include <functional>
#include <optional>
#include <string>
#include <string_view>

#include "core/common/log_priority.h"

namespace atlas {

struct DriverLogLine {
  LogPriority priority = LogPriority::kInfo;
  std::string text;  // "<who>: <what>", one line
  bool operator==(const DriverLogLine&) const = default;
};
using DriverLogSink = std::function<void(const DriverLogLine&)>;

class DriverLog {
 public:
  explicit DriverLog(std::string who) : who_(std::move(who)) {}

  // Info, the first time only: the driver starts.
  std::optional<DriverLogLine> Connecting();
  // Err: an open or start-up failed, or a session ended before its first message; said when
  // `reason` differs from the last failure said since the device last delivered.
  std::optional<DriverLogLine> AttemptFailed(std::string_view reason);
  // Notice: the first message of a session (once per session).
  std::optional<DriverLogLine> Delivering();
  // Warning: a session that delivered ended (`reason`: why); the driver reconnects.
  std::optional<DriverLogLine> Lost(std::string_view reason);
  // Warning: a delivering device went silent; notice when data comes again.
  std::optional<DriverLogLine> Stalled(std::string_view reason);
  std::optional<DriverLogLine> Resumed();
  // Err: the driver gave up (attempt budget spent, or the reader stopped).
  std::optional<DriverLogLine> GaveUp(std::string_view reason);
  // Info: stopped (by the daemon).
  std::optional<DriverLogLine> Stopped();
  // What the device says of itself or its link (a unit mismatch, an interface down, refused
  // scheduling), at `priority`: said when `text` differs from the last condition said.
  std::optional<DriverLogLine> Condition(LogPriority priority, std::string_view text);

 private:
  DriverLogLine Line(LogPriority p, std::string_view what) const;

  std::string who_;
  bool started_ = false;
  bool delivering_ = false;  // this session has decoded a message
  bool stalled_ = false;     // a stall was said and no data came since
  int failed_attempts_ = 0;  // since the device last delivered
  std::string last_failure_;
  std::string last_condition_;
};

}  // namespace atlas
