// libFuzzer target: the input as the text of a CARMEN log, fed line by line to the log builder
// (skip mode and line-order clock, then stop-at-first-error mode and the ipc clock). Invariants
// are checked with traps: ranges are non-negative numbers or kNoReturn, events come out
// time-ordered, and every line is either counted or reported as malformed.

#include <cmath>
#include <cstddef>
#include <cstdint>
#include <string_view>

#include "drivers/framing/fuzz_check.h"
#include "logs/carmen/carmen_log.h"

namespace {

using namespace atlas::carmen;

atlas::carmen::CarmenLog Feed(std::string_view text, const CarmenLogOptions& options,
                              int64_t& lines_fed) {
  CarmenLogBuilder builder(options, "fuzz");
  lines_fed = 0;
  size_t pos = 0;
  while (pos < text.size()) {
    size_t end = text.find('\n', pos);
    if (end == std::string_view::npos) end = text.size();
    const std::string_view line = text.substr(pos, end - pos);
    pos = end + 1;
    ++lines_fed;
    if (!builder.AddLine(lines_fed, line)) {
      FUZZ_CHECK(!options.skip_bad_lines && !builder.error().empty());
      break;
    }
  }
  return builder.Finish();
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, std::size_t size) {
  const std::string_view text(reinterpret_cast<const char*>(data), size);
  CarmenLogOptions skip = CarmenLogOptions::ForCorrectedLog();
  skip.skip_bad_lines = true;
  int64_t fed = 0;
  const CarmenLog a = Feed(text, skip, fed);
  FUZZ_CHECK(a.lines == fed);
  FUZZ_CHECK(a.odometry_events == 0);
  for (size_t i = 1; i < a.events.size(); ++i) {
    FUZZ_CHECK(StampOf(a.events[i - 1].event) <= StampOf(a.events[i].event));
  }
  const CarmenLog b = Feed(text, CarmenLogOptions{}, fed);
  for (size_t i = 1; i < b.events.size(); ++i) {
    FUZZ_CHECK(StampOf(b.events[i - 1].event) <= StampOf(b.events[i].event));
  }
  FUZZ_CHECK(b.bad_lines <= 1);
  for (const CarmenEvent& e : b.events) {
    if (const auto* scan = std::get_if<atlas::LaserScan>(&e.event)) {
      for (float r : scan->ranges) FUZZ_CHECK(r >= 0.0f && !std::isnan(r));  // kNoReturn is +inf
    }
  }
  return 0;
}
