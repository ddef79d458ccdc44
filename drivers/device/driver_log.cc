#include "drivers/device/driver_log.h"

namespace atlas {

DriverLogLine DriverLog::Line(LogPriority p, std::string_view what) const {
  return {p, who_ + ": " + std::string(what)};
}

std::optional<DriverLogLine> DriverLog::Connecting() {
  if (started_) return std::nullopt;
  started_ = true;
  return Line(LogPriority::kInfo, "connecting");
}

std::optional<DriverLogLine> DriverLog::AttemptFailed(std::string_view reason) {
  delivering_ = false;
  stalled_ = false;
  ++failed_attempts_;
  if (reason == last_failure_) return std::nullopt;
  last_failure_ = reason;
  return Line(LogPriority::kErr, std::string(reason) + "; retrying");
}

std::optional<DriverLogLine> DriverLog::Delivering() {
  if (delivering_) return std::nullopt;
  delivering_ = true;
  std::string what = "running";
  if (failed_attempts_ > 0)
    what += " after " + std::to_string(failed_attempts_) + " failed attempt" +
            (failed_attempts_ == 1 ? "" : "s");
  failed_attempts_ = 0;
  last_failure_.clear();
  return Line(LogPriority::kNotice, what);
}

std::optional<DriverLogLine> DriverLog::Lost(std::string_view reason) {
  if (!delivering_) return AttemptFailed(reason);
  delivering_ = false;
  stalled_ = false;
  return Line(LogPriority::kWarning, "lost (" + std::string(reason) + "); reconnecting");
}

std::optional<DriverLogLine> DriverLog::Stalled(std::string_view reason) {
  if (!delivering_ || stalled_) return std::nullopt;
  stalled_ = true;
  return Line(LogPriority::kWarning, "stalled: " + std::string(reason));
}

std::optional<DriverLogLine> DriverLog::Resumed() {
  if (!stalled_) return std::nullopt;
  stalled_ = false;
  return Line(LogPriority::kNotice, "data again");
}

std::optional<DriverLogLine> DriverLog::GaveUp(std::string_view reason) {
  delivering_ = false;
  stalled_ = false;
  return Line(LogPriority::kErr, "failed: " + std::string(reason) + "; giving up");
}

std::optional<DriverLogLine> DriverLog::Stopped() {
  delivering_ = false;
  stalled_ = false;
  return Line(LogPriority::kInfo, "stopped");
}

std::optional<DriverLogLine> DriverLog::Condition(LogPriority priority, std::string_view text) {
  if (text == last_condition_) return std::nullopt;
  last_condition_ = text;
  return Line(priority, text);
}

}  // namespace atlas
