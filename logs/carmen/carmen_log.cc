#include "logs/carmen/carmen_log.h"

#include <sys/stat.h>
#include <zlib.h>

#include <algorithm>
#include <cerrno>
#include <cmath>
#include <cstdio>
#include <cstring>

namespace atlas::carmen {
namespace {

constexpr size_t kMaxReportedBadLines = 10;

std::string_view StaticMessageName(std::string_view m) {
  static constexpr std::string_view kNames[] = {
      "ODOM", "FLASER", "ROBOTLASER1", "RAWLASER1", "RAWLASER2", "RAWLASER3", "RAWLASER4"};
  for (std::string_view n : kNames) {
    if (n == m) return n;
  }
  return "?";
}

bool IsOdometry(const CarmenEvent& e) { return std::holds_alternative<OdometrySample>(e.event); }

// Stamp order; on equal stamps line order, and odometry before a scan of the same line.
bool EventBefore(const CarmenEvent& a, const CarmenEvent& b) {
  const Time ta = atlas::StampOf(a.event), tb = atlas::StampOf(b.event);
  if (ta != tb) return ta < tb;
  if (a.line != b.line) return a.line < b.line;
  return IsOdometry(a) && !IsOdometry(b);
}

}  // namespace

const char* ToString(ReadStatus s) {
  switch (s) {
    case ReadStatus::kOk:
      return "ok";
    case ReadStatus::kCannotOpen:
      return "cannot open";
    case ReadStatus::kReadError:
      return "read error";
    case ReadStatus::kBadLine:
      return "malformed line";
    case ReadStatus::kBadOptions:
      return "bad options";
  }
  return "?";
}

CarmenLogOptions CarmenLogOptions::ForCorrectedLog() {
  CarmenLogOptions o;
  o.clock = Clock::kLineOrder;
  o.reference_trajectory = true;
  return o;
}

std::string ClampNote(const CarmenLog& log) {
  if (log.largest_range_returns < kClampBeams) return "";
  char b[320];
  std::snprintf(b, sizeof(b),
                "%lld beams read %.2f m, the log's largest range, and are used as returns; if "
                "%.2f m is this log's no-return value (a clamp), read it with --log-max-range %g",
                static_cast<long long>(log.largest_range_returns), log.largest_range,
                log.largest_range, static_cast<double>(log.largest_range));
  return b;
}

std::string CarmenLogOptions::Validate() const {
  if (!(line_period_s > 0.0) || !std::isfinite(line_period_s)) {
    return "line_period_s must be > 0";
  }
  if (!(max_range_m >= 0.0) || !std::isfinite(max_range_m)) {
    return "max_range_m must be >= 0 (0 = the log's own maximum)";
  }
  if (max_line_bytes < 64) return "max_line_bytes must be >= 64";
  return {};
}

CarmenLogBuilder::CarmenLogBuilder(const CarmenLogOptions& options, std::string source_name)
    : options_(options), source_name_(std::move(source_name)) {}

Time CarmenLogBuilder::StampOf(int64_t line_number, double ipc_timestamp) const {
  if (options_.clock == Clock::kLineOrder) {
    return FromSeconds(static_cast<double>(line_number) * options_.line_period_s);
  }
  return FromSeconds(ipc_timestamp);
}

LaserScan CarmenLogBuilder::MakeScan(const LaserRecord& rec, Time stamp) {
  LaserScan scan;
  scan.stamp = stamp;
  scan.angle_min = static_cast<float>(rec.start_angle);
  scan.angle_increment = static_cast<float>(rec.angular_resolution);
  double max_range = options_.max_range_m;
  if (max_range <= 0.0) max_range = rec.max_range > 0.0 ? rec.max_range : kFlaserMaxRange;
  scan.max_range = static_cast<float>(max_range);
  scan.ranges = rec.ranges;
  for (float& r : scan.ranges) {
    if (r > log_.largest_range) {
      log_.largest_range = r;
      log_.largest_range_count = 0;
      log_.largest_range_returns = 0;
    }
    if (r == log_.largest_range) {
      ++log_.largest_range_count;
      if (r < scan.max_range) ++log_.largest_range_returns;
    }
    if (r >= scan.max_range) {
      r = kNoReturn;
      ++log_.no_return_beams;
    }
  }
  log_.beams += static_cast<int64_t>(scan.ranges.size());
  if (rec.laser_pose && rec.odometry_pose) {
    scan.sensor_pose = Between(*rec.odometry_pose, *rec.laser_pose);
  }
  return scan;
}

bool CarmenLogBuilder::AddBadLine(int64_t line_number, const std::string& reason) {
  if (!error_.empty()) return false;
  ++log_.lines;
  ++log_.bad_lines;
  const std::string where = source_name_ + ":" + std::to_string(line_number) + ": " + reason;
  if (log_.bad_line_reasons.size() < kMaxReportedBadLines) log_.bad_line_reasons.push_back(where);
  if (options_.skip_bad_lines) return true;
  error_ = where;
  return false;
}

bool CarmenLogBuilder::AddLine(int64_t line_number, std::string_view text) {
  if (!error_.empty()) return false;
  ParsedLine p = ParseLine(text);
  if (!p.ok()) return AddBadLine(line_number, p.reason);
  ++log_.lines;
  if (p.message.empty()) {
    ++log_.comment_or_blank_lines;
    return true;
  }
  ++log_.lines_by_message[p.message];
  if (p.kind == LineKind::kIgnored) return true;

  const auto note_stamp = [this](Time t) {
    if (any_stamp_ && t < latest_stamp_) ++log_.out_of_order_lines;
    if (!any_stamp_ || t > latest_stamp_) latest_stamp_ = t;
    any_stamp_ = true;
  };

  if (p.kind == LineKind::kOdometry) {
    const Time stamp = StampOf(line_number, p.odometry.ipc_timestamp);
    note_stamp(stamp);
    const Pose2 pose{p.odometry.pose.x, p.odometry.pose.y, WrapAngle(p.odometry.pose.theta)};
    if (options_.reference_trajectory) {
      log_.reference.push_back(ReferencePose{line_number, false, TruthSample{stamp, pose}});
      return true;
    }
    CarmenEvent e;
    e.line = line_number;
    e.message = StaticMessageName(p.message);
    e.log_timestamp = p.odometry.ipc_timestamp;
    e.event = OdometrySample{stamp, pose};
    odom_line_events_.push_back(std::move(e));
    return true;
  }

  const LaserRecord& rec = p.laser;
  const Time stamp = StampOf(line_number, rec.ipc_timestamp);
  note_stamp(stamp);
  CarmenEvent e;
  e.line = line_number;
  e.message = StaticMessageName(p.message);
  e.log_timestamp = rec.ipc_timestamp;
  e.laser_pose = rec.laser_pose;
  e.odometry_pose = rec.odometry_pose;
  if (rec.odometry_pose) {
    const Pose2 pose{rec.odometry_pose->x, rec.odometry_pose->y,
                     WrapAngle(rec.odometry_pose->theta)};
    if (options_.reference_trajectory) {
      log_.reference.push_back(ReferencePose{line_number, true, TruthSample{stamp, pose}});
    } else {
      CarmenEvent o = e;
      o.event = OdometrySample{stamp, pose};
      laser_odometry_events_.push_back(std::move(o));
    }
  }
  e.event = MakeScan(rec, stamp);
  log_.events.push_back(std::move(e));
  ++log_.laser_events;
  return true;
}

CarmenLog CarmenLogBuilder::Finish() {
  if (!options_.reference_trajectory) {
    bool from_odom_lines = true;
    switch (options_.odometry) {
      case OdometrySource::kAuto:
        from_odom_lines = !odom_line_events_.empty();
        break;
      case OdometrySource::kOdomLines:
        from_odom_lines = true;
        break;
      case OdometrySource::kLaserLines:
        from_odom_lines = false;
        break;
    }
    std::vector<CarmenEvent>& odo = from_odom_lines ? odom_line_events_ : laser_odometry_events_;
    log_.odometry_events = static_cast<int64_t>(odo.size());
    log_.events.insert(log_.events.end(), std::make_move_iterator(odo.begin()),
                       std::make_move_iterator(odo.end()));
  }
  odom_line_events_.clear();
  laser_odometry_events_.clear();
  std::stable_sort(log_.events.begin(), log_.events.end(), EventBefore);
  std::stable_sort(
      log_.reference.begin(), log_.reference.end(),
      [](const ReferencePose& a, const ReferencePose& b) { return a.truth.stamp < b.truth.stamp; });
  return std::move(log_);
}

namespace {

// What went wrong in a gzip stream (zlib's gzerror), for a person who has to fix the file.
std::string GzipReadError(const std::string& path, int64_t complete_lines, int zerr,
                          std::string zmessage) {
  if (zmessage.rfind(path + ": ", 0) == 0) zmessage.erase(0, path.size() + 2);  // zlib's prefix
  const std::string after = " after line " + std::to_string(complete_lines);
  if (zerr == Z_BUF_ERROR) {
    return path + " is truncated (the gzip stream ends early)" + after +
           ": copy or download it again";
  }
  if (zerr == Z_DATA_ERROR && zmessage.find("check") != std::string::npos) {
    // "incorrect data check" (CRC-32) or "incorrect length check" in the gzip trailer. zlib
    // drops the data it decompressed with the check, so no line number: it says little.
    return path + ": gzip CRC error (" + zmessage +
           "): the file is corrupt; copy or download it again";
  }
  if (zerr == Z_DATA_ERROR) {
    return path + ": corrupt gzip data (" + zmessage + ")" + after + ": copy or download it again";
  }
  return path + ": read error" + after + " (" + zmessage + ")";
}

}  // namespace

CarmenReadResult ReadCarmenLog(const std::string& path, const CarmenLogOptions& options,
                               const ReadProgress& progress) {
  CarmenReadResult result;
  if (std::string bad = options.Validate(); !bad.empty()) {
    result.status = ReadStatus::kBadOptions;
    result.error = "CARMEN reader options: " + bad;
    return result;
  }
  errno = 0;
  gzFile f = gzopen(path.c_str(), "rb");
  if (f == nullptr) {
    result.status = ReadStatus::kCannotOpen;
    result.error = path + ": cannot open (" +
                   (errno != 0 ? std::string(std::strerror(errno)) : "out of memory") + ")";
    return result;
  }
  gzbuffer(f, 1 << 17);
  struct stat st {};
  const int64_t file_size = stat(path.c_str(), &st) == 0 ? static_cast<int64_t>(st.st_size) : 0;
  CarmenLogBuilder builder(options, path);
  std::vector<char> chunk(1 << 16);
  std::string line;
  int64_t line_number = 0;
  bool too_long = false;
  bool stopped = false;
  const auto finish_line = [&]() {
    ++line_number;
    bool ok;
    if (too_long) {
      ok = builder.AddBadLine(
          line_number, "line longer than " + std::to_string(options.max_line_bytes) + " bytes");
    } else {
      ok = builder.AddLine(line_number, line);
    }
    line.clear();
    too_long = false;
    if (!ok) stopped = true;
  };
  while (!stopped) {
    if (gzgets(f, chunk.data(), static_cast<int>(chunk.size())) == nullptr) break;
    const size_t n = std::strlen(chunk.data());
    const bool ends_line = n > 0 && chunk[n - 1] == '\n';
    if (!too_long) {
      line.append(chunk.data(), ends_line ? n - 1 : n);
      if (line.size() > options.max_line_bytes) {
        too_long = true;
        line.clear();
      }
    }
    if (ends_line) finish_line();
    if (progress && ends_line && line_number % 4096 == 0) progress(gzoffset(f), file_size);
  }
  if (progress) progress(file_size, file_size);
  int zerr = Z_OK;
  const char* zmsg = gzerror(f, &zerr);
  const bool read_failed = !stopped && zerr != Z_OK && zerr != Z_STREAM_END;
  const std::string zmessage = zmsg != nullptr ? zmsg : "";
  // A last line without '\n' is a line, unless the gzip stream broke there: then it is the
  // piece of a line that the damage left, not a malformed line.
  if (!stopped && !read_failed && (!line.empty() || too_long)) finish_line();
  gzclose(f);
  if (stopped) {
    result.status = ReadStatus::kBadLine;
    result.error = builder.error();
    return result;
  }
  if (read_failed) {
    result.status = ReadStatus::kReadError;
    result.error = GzipReadError(path, line_number, zerr, zmessage);
    return result;
  }
  result.log = builder.Finish();
  return result;
}

}  // namespace atlas::carmen
