#pragma once
// A tour: several CARMEN logs replayed as one run (docs/results.md, "A tour of the real logs"),
// to measure the step time of one atlas over many buildings. Pure functions; atlas-carmen
// --dump-carmen --append owns the files.
//
// - ContinueRun moves a log's events so that they go on from where a run ended: the stamps are
//   shifted so that the first event comes `gap` after the end, and every odometry pose (the
//   odometry events, and the poses laser lines carry) is moved by the one rigid transform that
//   puts the log's first odometry pose on the end pose. The robot is carried from one building
//   to the next without its odometry moving; nothing else changes.
// - CarmenLines writes events as CARMEN lines (sim/carmen_writer.h): an ODOM line per odometry
//   event, a FLASER line per laser scan with the odometry interpolated at its stamp. FLASER
//   lines state no angles: a scan is written only when reading its line back gives its own
//   angles (n beams as carmen::GuessFlaserFov lays them out); scans that do not, or that have no
//   odometry around them, are counted and left out.

#include <cstdint>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "core/common/sensor_types.h"
#include "logs/carmen/carmen_log.h"

namespace atlas::eval {

// `events` time-ordered. Without an odometry event the events are only shifted in time.
std::vector<carmen::CarmenEvent> ContinueRun(std::vector<carmen::CarmenEvent> events,
                                             const OdometrySample& end, Duration gap);

struct CarmenLinesResult {
  std::string text;
  int64_t odometry_lines = 0;
  int64_t laser_lines = 0;
  int64_t scans_without_odometry = 0;  // before the first or after the last odometry event
  int64_t scans_not_flaser = 0;        // angles a FLASER line cannot state
};
CarmenLinesResult CarmenLines(const std::vector<carmen::CarmenEvent>& events, const char* hostname);

// The odometry of the last ODOM line of `lines` (whole CARMEN lines, such as the end of a log
// CarmenLines wrote) that the reader takes, or none: where a run continues.
std::optional<OdometrySample> LastOdometryIn(std::string_view lines);

}  // namespace atlas::eval
