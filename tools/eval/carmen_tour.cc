#include "tools/eval/carmen_tour.h"

#include <cmath>
#include <numbers>
#include <optional>
#include <variant>

#include "logs/carmen/carmen_line.h"
#include "sim/carmen_writer.h"
#include "tools/eval/trajectory_files.h"

namespace atlas::eval {
namespace {

// Whether a FLASER line of `scan`'s beams, read back, has the scan's own angles.
bool FlaserLayout(const LaserScan& scan) {
  const int n = static_cast<int>(scan.ranges.size());
  if (n < 2) return false;
  const double increment = carmen::GuessFlaserAngleIncrement(n);
  constexpr double kTolerance = 1e-6;  // radians; the scan's angles are floats
  return std::abs(scan.angle_min - (-std::numbers::pi / 2.0)) < kTolerance &&
         std::abs(scan.angle_increment - increment) < kTolerance;
}

}  // namespace

std::vector<carmen::CarmenEvent> ContinueRun(std::vector<carmen::CarmenEvent> events,
                                             const OdometrySample& end, Duration gap) {
  if (events.empty()) return events;
  const Duration shift = end.stamp + gap - StampOf(events.front().event);
  std::optional<Pose2> move;
  for (const carmen::CarmenEvent& e : events) {
    if (const auto* o = std::get_if<OdometrySample>(&e.event)) {
      move = Compose(end.pose, Inverse(o->pose));
      break;
    }
  }
  for (carmen::CarmenEvent& e : events) {
    e.log_timestamp += ToSeconds(shift);
    std::visit([&](auto& x) { x.stamp += shift; }, e.event);
    if (!move) continue;
    if (auto* o = std::get_if<OdometrySample>(&e.event)) o->pose = Compose(*move, o->pose);
    if (e.odometry_pose) e.odometry_pose = Compose(*move, *e.odometry_pose);
    if (e.laser_pose) e.laser_pose = Compose(*move, *e.laser_pose);
  }
  return events;
}

CarmenLinesResult CarmenLines(const std::vector<carmen::CarmenEvent>& events,
                              const char* hostname) {
  CarmenLinesResult r;
  const TimedTrajectory at_scans = OdometryAtScans(events);
  for (const carmen::CarmenEvent& e : events) {
    if (const auto* o = std::get_if<OdometrySample>(&e.event)) {
      sim::AppendOdomLine(&r.text, *o, o->linear_velocity, o->angular_velocity, hostname);
      ++r.odometry_lines;
    } else if (const auto* scan = std::get_if<LaserScan>(&e.event)) {
      const std::optional<Pose2> odometry = at_scans.PoseAt(scan->stamp, Duration::zero());
      if (!odometry) {
        ++r.scans_without_odometry;
      } else if (!FlaserLayout(*scan)) {
        ++r.scans_not_flaser;
      } else {
        sim::AppendFlaserLine(&r.text, *scan, *odometry, hostname);
        ++r.laser_lines;
      }
    }
  }
  return r;
}

std::optional<OdometrySample> LastOdometryIn(std::string_view lines) {
  size_t end = lines.size();
  while (end > 0) {
    const size_t start = lines.rfind('\n', end - 1);
    const size_t from = start == std::string_view::npos ? 0 : start + 1;
    const std::string_view line = lines.substr(from, end - from);
    end = from == 0 ? 0 : from - 1;
    if (!line.starts_with("ODOM ")) continue;
    carmen::CarmenLogBuilder builder(carmen::CarmenLogOptions{}, "");
    if (!builder.AddLine(1, line)) continue;
    const carmen::CarmenLog log = builder.Finish();
    if (!log.events.empty()) {
      if (const auto* o = std::get_if<OdometrySample>(&log.events.front().event)) return *o;
    }
  }
  return std::nullopt;
}

}  // namespace atlas::eval
