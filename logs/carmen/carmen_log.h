#pragma once
// A CARMEN log as time-ordered sensor events (the plain structs of core/common/sensor_types.h),
// each with the log line it came from.
//
// CarmenLogBuilder turns lines into events without I/O; ReadCarmenLog() feeds it from a file,
// plain or gzip-compressed (zlib reads both).
//
// Clock: by default an event's stamp is the line's ipc_timestamp. The "corrected" logs
// (Radish data republished with GMapping poses) have unusable timestamps; with
// Clock::kLineOrder the stamp of line k is k * line_period_s, so the order of lines is the
// clock and stamps are unique.
//
// Odometry: from ODOM lines, or, when a log has no ODOM line at all (mit-csail.clf), from the
// odom_x odom_y odom_theta fields of its laser lines (OdometrySource::kAuto). With
// reference_trajectory set (corrected logs) no odometry event is produced: the poses of ODOM
// lines and the robot poses of laser lines become the reference trajectory instead, from which
// odometry can be synthesised (reference_odometry.h).
//
// Ranges at or above the maximum range are no-return codes (kNoReturn): SICK LMS logs write
// 81.83..81.91 m for "no echo" / "dazzled"; CARMEN takes 80 m as the FLASER maximum. Some logs
// clamp at a lower value (aces-corrected: 50 m); set max_range_m for them. The largest range and
// how often it occurs are reported to help spot such a clamp.

#include <cstdint>
#include <functional>
#include <map>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "core/common/sensor_types.h"
#include "logs/carmen/carmen_line.h"

namespace atlas::carmen {

enum class Clock { kIpcTimestamp, kLineOrder };
enum class OdometrySource { kAuto, kOdomLines, kLaserLines };

// CARMEN's maximum range for FLASER lines, which do not state one.
inline constexpr double kFlaserMaxRange = 80.0;

struct CarmenLogOptions {
  Clock clock = Clock::kIpcTimestamp;
  double line_period_s = 0.05;  // Clock::kLineOrder: seconds per line
  OdometrySource odometry = OdometrySource::kAuto;
  bool reference_trajectory = false;  // poses -> reference, no odometry events
  // Ranges >= this are kNoReturn. 0: the line's own maximum_range, or kFlaserMaxRange.
  double max_range_m = 0.0;
  // Count malformed lines and go on instead of failing at the first.
  bool skip_bad_lines = false;
  // Lines longer than this are malformed.
  size_t max_line_bytes = 1 << 20;

  // Settings for the corrected logs: line-order clock and reference trajectory.
  static CarmenLogOptions ForCorrectedLog();
  // Empty when valid, else what is wrong.
  std::string Validate() const;
};

struct CarmenEvent {
  int64_t line = 0;            // 1-based line number in the log
  std::string_view message;    // "ODOM", "FLASER", ... (static storage)
  double log_timestamp = 0.0;  // the line's ipc_timestamp as written
  SensorEvent event;           // OdometrySample or LaserScan
  // Laser lines that carry them: the pose of the laser and the odometry pose of the robot.
  std::optional<Pose2> laser_pose;
  std::optional<Pose2> odometry_pose;
};

struct ReferencePose {
  int64_t line = 0;
  bool at_laser = false;  // from a laser line (a scan was taken here)
  TruthSample truth;
};

struct CarmenLog {
  std::vector<CarmenEvent> events;                  // stamps non-decreasing; line order on ties
  std::vector<ReferencePose> reference;             // reference_trajectory only; line order
  std::map<std::string, int64_t> lines_by_message;  // every message name seen, ignored included
  int64_t lines = 0;
  int64_t comment_or_blank_lines = 0;
  int64_t bad_lines = 0;
  std::vector<std::string> bad_line_reasons;  // the first few, "line N: ..."
  int64_t out_of_order_lines = 0;             // events stamped earlier than an earlier line's event
  int64_t odometry_events = 0;
  int64_t laser_events = 0;
  int64_t beams = 0;
  int64_t no_return_beams = 0;
  float largest_range = 0.0f;  // largest range as written
  int64_t largest_range_count = 0;
  int64_t largest_range_returns = 0;  // of those, beams kept as returns (below the maximum)
};

// A log that writes its no-return value below the maximum range it is read with (aces-corrected
// writes 50 m) reads that value as a return on every such beam. When the log's largest range
// was kept as a return on at least kClampBeams beams (no real scene gives one range that often),
// a note in words naming the value and the option that reads it as no return; else "".
inline constexpr int64_t kClampBeams = 100;
std::string ClampNote(const CarmenLog& log);

enum class ReadStatus { kOk, kCannotOpen, kReadError, kBadLine, kBadOptions };
const char* ToString(ReadStatus s);

struct CarmenReadResult {
  ReadStatus status = ReadStatus::kOk;
  std::string error;  // "<file>:<line>: <what>" when not kOk
  CarmenLog log;
  bool ok() const { return status == ReadStatus::kOk; }
};

// Turns log lines, in order, into a CarmenLog. No I/O.
class CarmenLogBuilder {
 public:
  // `options` must be valid. `source_name` prefixes error messages (the file name).
  CarmenLogBuilder(const CarmenLogOptions& options, std::string source_name);

  // Adds line number `line_number` (1-based, increasing). Returns false when the line is
  // malformed and skip_bad_lines is off; error() then says why. Later calls are ignored.
  bool AddLine(int64_t line_number, std::string_view text);
  // Records a malformed line found by the caller (e.g. too long).
  bool AddBadLine(int64_t line_number, const std::string& reason);

  const std::string& error() const { return error_; }
  // Orders the events and hands the log over. Call once.
  CarmenLog Finish();

 private:
  Time StampOf(int64_t line_number, double ipc_timestamp) const;
  LaserScan MakeScan(const LaserRecord& rec, Time stamp);

  CarmenLogOptions options_;
  std::string source_name_;
  std::string error_;
  CarmenLog log_;
  std::vector<CarmenEvent> odom_line_events_;
  std::vector<CarmenEvent> laser_odometry_events_;  // odometry from laser lines
  Time latest_stamp_{};
  bool any_stamp_ = false;
};

// Reads a CARMEN log file, plain or gzip-compressed.
// `progress`, when set, is called now and then (every few thousand lines) with the bytes of the
// file read so far (of the compressed file for a .gz) and the file's size.
using ReadProgress = std::function<void(int64_t bytes_read, int64_t bytes_total)>;
CarmenReadResult ReadCarmenLog(const std::string& path, const CarmenLogOptions& options,
                               const ReadProgress& progress = {});

}  // namespace atlas::carmen
