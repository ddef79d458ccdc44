#include "logs/carmen/carmen_line.h"

#include <cmath>
#include <numbers>

#include "core/common/parse_number.h"
#include "core/common/quote_for_message.h"

namespace atlas::carmen {
namespace {

constexpr double kPi = std::numbers::pi;

std::vector<std::string_view> SplitFields(std::string_view line) {
  std::vector<std::string_view> out;
  size_t i = 0;
  while (i < line.size()) {
    while (i < line.size() && (line[i] == ' ' || line[i] == '\t' || line[i] == '\r')) ++i;
    const size_t start = i;
    while (i < line.size() && line[i] != ' ' && line[i] != '\t' && line[i] != '\r') ++i;
    if (i > start) out.push_back(line.substr(start, i - start));
  }
  return out;
}

bool IsMessageName(std::string_view w) {
  if (w.empty() || !(w[0] >= 'A' && w[0] <= 'Z')) return false;
  for (char c : w) {
    if (!((c >= 'A' && c <= 'Z') || (c >= '0' && c <= '9') || c == '_')) return false;
  }
  return true;
}

// Walks the fields of one line, recording the first error.
class FieldCursor {
 public:
  FieldCursor(const std::vector<std::string_view>& fields, ParsedLine& out)
      : fields_(fields), out_(out) {}

  bool failed() const { return !out_.ok(); }

  std::string_view Word(const char* what) {
    if (failed()) return {};
    if (next_ >= fields_.size()) {
      Fail(LineError::kMissingFields,
           std::string("line ends before field ") + std::to_string(next_ + 1) + " (" + what + ")");
      return {};
    }
    return fields_[next_++];
  }

  double Number(const char* what) {
    const size_t index = next_;
    std::string_view w = Word(what);
    if (failed()) return 0.0;
    if (!w.empty() && w[0] == '+') w.remove_prefix(1);
    double v = 0.0;
    if (!ParseNumber(w, &v)) {
      Fail(LineError::kBadNumber, std::string("field ") + std::to_string(index + 1) + " (" + what +
                                      ") is " + QuoteForMessage(w) + ", not a number");
      return 0.0;
    }
    return v;
  }

  int Count(const char* what) {
    const size_t index = next_;
    const double v = Number(what);
    if (failed()) return 0;
    if (v < 0 || v > kMaxBeams || v != std::floor(v)) {
      Fail(LineError::kBadCount, std::string("field ") + std::to_string(index + 1) + " (" + what +
                                     ") is " + std::string(fields_[index]) +
                                     ", not a count in 0.." + std::to_string(kMaxBeams));
      return 0;
    }
    return static_cast<int>(v);
  }

  Pose2 Pose(const char* what) {
    Pose2 p;
    p.x = Number(what);
    p.y = Number(what);
    p.theta = Number(what);
    return p;
  }

  std::vector<float> Ranges(int n) {
    std::vector<float> r;
    if (failed()) return r;
    if (fields_.size() - next_ < static_cast<size_t>(n)) {
      Fail(LineError::kMissingFields, "line has " + std::to_string(fields_.size() - next_) +
                                          " fields left, fewer than the " + std::to_string(n) +
                                          " ranges it announces");
      return r;
    }
    r.reserve(n);
    for (int i = 0; i < n && !failed(); ++i) {
      const size_t index = next_;
      const double v = Number("range");
      if (!failed() && v < 0.0) {
        Fail(LineError::kBadRange, "range " + std::to_string(i) + " (field " +
                                       std::to_string(index + 1) +
                                       ") is negative: " + std::string(fields_[index]));
      }
      r.push_back(static_cast<float>(v));
    }
    return r;
  }

  void SkipNumbers(int n, const char* what) {
    for (int i = 0; i < n && !failed(); ++i) Number(what);
  }

  void ExpectEnd() {
    if (failed() || next_ == fields_.size()) return;
    Fail(LineError::kExtraFields, std::to_string(fields_.size() - next_) +
                                      " unexpected field(s) after the last one, starting with " +
                                      QuoteForMessage(fields_[next_]));
  }

 private:
  void Fail(LineError e, std::string reason) {
    out_.error = e;
    out_.reason = out_.message + ": " + std::move(reason);
  }

  const std::vector<std::string_view>& fields_;
  ParsedLine& out_;
  size_t next_ = 1;
};

void ParseTail(FieldCursor& c, double& ipc, std::string& host, double& logger) {
  ipc = c.Number("ipc_timestamp");
  host = std::string(c.Word("hostname"));
  logger = c.Number("logger_timestamp");
  c.ExpectEnd();
}

void ParseOdom(FieldCursor& c, ParsedLine& out) {
  OdometryRecord& o = out.odometry;
  o.pose = c.Pose("x y theta");
  o.tv = c.Number("tv");
  o.rv = c.Number("rv");
  o.accel = c.Number("accel");
  ParseTail(c, o.ipc_timestamp, o.hostname, o.logger_timestamp);
}

void ParseFlaser(FieldCursor& c, ParsedLine& out) {
  LaserRecord& l = out.laser;
  const int n = c.Count("num_readings");
  l.ranges = c.Ranges(n);
  l.laser_pose = c.Pose("x y theta");
  l.odometry_pose = c.Pose("odom_x odom_y odom_theta");
  ParseTail(c, l.ipc_timestamp, l.hostname, l.logger_timestamp);
  l.fov = GuessFlaserFov(n);
  l.start_angle = -kPi / 2.0;
  l.angular_resolution = GuessFlaserAngleIncrement(n);
}

// RAWLASER<k> and ROBOTLASER1 share the header and the beam block.
void ParseConfiguredLaser(FieldCursor& c, ParsedLine& out, bool robot) {
  LaserRecord& l = out.laser;
  c.Number("laser_type");
  l.start_angle = c.Number("start_angle");
  l.fov = c.Number("field_of_view");
  l.angular_resolution = c.Number("angular_resolution");
  l.max_range = c.Number("maximum_range");
  c.Number("accuracy");
  c.Number("remission_mode");
  const int n = c.Count("num_readings");
  l.ranges = c.Ranges(n);
  const int m = c.Count("num_remissions");
  c.SkipNumbers(m, "remission");
  if (robot) {
    l.laser_pose = c.Pose("laser_pose_x laser_pose_y laser_pose_theta");
    l.odometry_pose = c.Pose("robot_pose_x robot_pose_y robot_pose_theta");
    c.SkipNumbers(5, "tv rv forward_safety_dist side_safety_dist turn_axis");
  }
  ParseTail(c, l.ipc_timestamp, l.hostname, l.logger_timestamp);
}

}  // namespace

const char* ToString(LineError e) {
  switch (e) {
    case LineError::kNone:
      return "ok";
    case LineError::kBadMessageName:
      return "bad message name";
    case LineError::kMissingFields:
      return "missing fields";
    case LineError::kExtraFields:
      return "extra fields";
    case LineError::kBadNumber:
      return "bad number";
    case LineError::kBadCount:
      return "bad count";
    case LineError::kBadRange:
      return "bad range";
  }
  return "?";
}

double GuessFlaserFov(int n) {
  if (n == 180) return kPi / 180.0 * 179.0;
  if (n == 360) return kPi / 180.0 * 179.5;
  if (n == 401) return kPi / 180.0 * 100.0;
  if (n == 400) return kPi / 180.0 * 99.75;
  return kPi;
}

double GuessFlaserAngleIncrement(int n) {
  if (n == 180 || n == 181) return kPi / 180.0;
  if (n == 360 || n == 361) return kPi / 360.0;
  if (n == 400 || n == 401) return kPi / 720.0;
  return n > 1 ? GuessFlaserFov(n) / (n - 1) : 0.0;
}

ParsedLine ParseLine(std::string_view line) {
  ParsedLine out;
  const std::vector<std::string_view> fields = SplitFields(line);
  if (fields.empty() || fields[0][0] == '#') return out;
  out.message = std::string(fields[0]);
  if (!IsMessageName(fields[0])) {
    out.error = LineError::kBadMessageName;
    out.reason = "first word " + QuoteForMessage(out.message) + " is not a CARMEN message name";
    return out;
  }
  FieldCursor c(fields, out);
  const std::string_view m = fields[0];
  if (m == "ODOM") {
    out.kind = LineKind::kOdometry;
    ParseOdom(c, out);
  } else if (m == "FLASER") {
    out.kind = LineKind::kLaser;
    out.laser.message = out.message;
    ParseFlaser(c, out);
  } else if (m.size() == 9 && m.substr(0, 8) == "RAWLASER" && m[8] >= '1' && m[8] <= '4') {
    out.kind = LineKind::kLaser;
    out.laser.message = out.message;
    out.laser.laser_id = m[8] - '0';
    ParseConfiguredLaser(c, out, /*robot=*/false);
  } else if (m == "ROBOTLASER1") {
    out.kind = LineKind::kLaser;
    out.laser.message = out.message;
    ParseConfiguredLaser(c, out, /*robot=*/true);
  }
  return out;
}

}  // namespace atlas::carmen
