#include "replay/laser_time_offset.h"

#include <cmath>
#include <cstdio>

#include "core/common/parse_number.h"
#include "core/mapper/odometry_track.h"

namespace atlas::replay {
namespace {

constexpr double kRadToDeg = 180.0 / M_PI;
constexpr int kMaxOffsets = 201;

Duration Seconds(double s) { return FromSeconds(s).time_since_epoch(); }

std::string Format(const char* fmt, auto... args) {
  char buf[256];
  std::snprintf(buf, sizeof buf, fmt, args...);
  return buf;
}

}  // namespace

HeadingCorrections MeasureHeadingCorrections(const std::vector<formats::FramePoseRow>& trajectory,
                                             const std::vector<OdometrySample>& odometry,
                                             Duration offset) {
  HeadingCorrections out;
  OdometryTrack track(odometry.size(), Duration::zero());
  for (const OdometrySample& s : odometry) track.Add(s);
  double sum_abs = 0.0, sum_sq = 0.0;
  for (size_t k = 1; k < trajectory.size(); ++k) {
    const formats::FramePoseRow& a = trajectory[k - 1];
    const formats::FramePoseRow& b = trajectory[k];
    if (a.frame != b.frame) continue;
    Pose2 odo_a, odo_b;
    if (track.PoseAt(a.stamp + offset, &odo_a) != OdometryLookup::kInterpolated ||
        track.PoseAt(b.stamp + offset, &odo_b) != OdometryLookup::kInterpolated) {
      ++out.skipped;
      continue;
    }
    const double c =
        WrapAngle(WrapAngle(b.pose.theta - a.pose.theta) - Between(odo_a, odo_b).theta);
    sum_abs += std::abs(c);
    sum_sq += c * c;
    ++out.pairs;
  }
  if (out.pairs > 0) {
    out.mean_abs_rad = sum_abs / out.pairs;
    out.rms_rad = std::sqrt(sum_sq / out.pairs);
  }
  return out;
}

std::string OffsetRange::Validate() const {
  if (!std::isfinite(from_s) || !std::isfinite(to_s) || !std::isfinite(step_s))
    return "offsets must be finite numbers";
  if (from_s < -1.0 || to_s > 1.0) return "offsets must lie within -1 s and +1 s";
  if (from_s > to_s) return "FROM must not be larger than TO";
  if (!(step_s > 0.0)) return "STEP must be positive";
  if ((to_s - from_s) / step_s + 1.0 > kMaxOffsets + 1e-9)
    return "at most " + std::to_string(kMaxOffsets) + " offsets (make STEP larger)";
  return "";
}

std::vector<double> OffsetRange::Offsets() const {
  std::vector<double> out;
  const int n = static_cast<int>(std::floor((to_s - from_s) / step_s + 1e-9)) + 1;
  for (int k = 0; k < n; ++k) {
    const double v = from_s + k * step_s;
    out.push_back(std::abs(v) < 1e-12 ? 0.0 : v);
  }
  return out;
}

bool ParseOffsetRange(const std::string& text, OffsetRange* range, std::string* error) {
  const size_t c1 = text.find(':');
  const size_t c2 = c1 == std::string::npos ? c1 : text.find(':', c1 + 1);
  OffsetRange r;
  if (c2 == std::string::npos || !ParseNumber(text.substr(0, c1).c_str(), &r.from_s) ||
      !ParseNumber(text.substr(c1 + 1, c2 - c1 - 1).c_str(), &r.to_s) ||
      !ParseNumber(text.substr(c2 + 1).c_str(), &r.step_s)) {
    *error = "want FROM:TO:STEP in seconds (e.g. -0.2:0:0.02), got '" + text + "'";
    return false;
  }
  if (std::string e = r.Validate(); !e.empty()) {
    *error = e + " (got '" + text + "')";
    return false;
  }
  *range = r;
  return true;
}

SweepBest BestOffset(const std::vector<OffsetSweepRow>& rows) {
  SweepBest best;
  for (size_t i = 0; i < rows.size(); ++i) {
    if (rows[i].corrections.pairs == 0) continue;
    if (best.index < 0 || rows[i].corrections.mean_abs_rad <
                              rows[static_cast<size_t>(best.index)].corrections.mean_abs_rad)
      best.index = static_cast<int>(i);
  }
  if (best.index < 0) return best;
  const size_t i = static_cast<size_t>(best.index);
  best.offset_s = rows[i].offset_s;
  if (i == 0 || i + 1 == rows.size() || rows[i - 1].corrections.pairs == 0 ||
      rows[i + 1].corrections.pairs == 0)
    return best;
  const double ym = rows[i - 1].corrections.mean_abs_rad, y0 = rows[i].corrections.mean_abs_rad,
               yp = rows[i + 1].corrections.mean_abs_rad;
  const double h = rows[i + 1].offset_s - rows[i].offset_s;
  const double curvature = ym - 2.0 * y0 + yp;
  if (!(curvature > 0.0)) return best;
  best.has_vertex = true;
  best.vertex_s = rows[i].offset_s + 0.5 * h * (ym - yp) / curvature;
  return best;
}

SweepResult SweepLaserTimeOffset(
    const std::vector<carmen::CarmenEvent>& events, const ReplayOptions& options,
    const OffsetRange& range, const std::string& out_dir,
    const std::function<void(const OffsetSweepRow&, int, int)>& on_row) {
  SweepResult result;
  if (std::string e = range.Validate(); !e.empty()) {
    result.error = "offsets: " + e;
    return result;
  }
  if (std::string e = CreateOutputDir(out_dir); !e.empty()) {
    result.error = e;
    return result;
  }
  std::vector<OdometrySample> odometry;
  for (const carmen::CarmenEvent& e : events)
    if (const auto* o = std::get_if<OdometrySample>(&e.event)) odometry.push_back(*o);
  const std::vector<double> offsets = range.Offsets();
  for (double offset : offsets) {
    ReplayOptions o = options;
    o.loop.laser_time_offset = Seconds(offset);
    const std::string dir = out_dir + Format("/offset_%+.3f", offset);
    ReplayResult r = RunReplay(events, o, dir);
    if (!r.error.empty()) {
      result.error = Format("offset %+.3f s: ", offset) + r.error;
      return result;
    }
    OffsetSweepRow row;
    row.offset_s = offset;
    row.corrections = MeasureHeadingCorrections(r.trajectory, odometry, Seconds(offset));
    row.summary = r.summary;
    result.rows.push_back(row);
    if (on_row) on_row(row, static_cast<int>(result.rows.size()), static_cast<int>(offsets.size()));
  }
  result.best = BestOffset(result.rows);
  if (std::string e = WriteOutputFile(out_dir, "sweep.tsv", FormatSweep(result)); !e.empty())
    result.error = e;
  return result;
}

std::string FormatSweep(const SweepResult& result) {
  std::string t =
      "# laser time offset sweep: offset_s pairs mean_abs_deg rms_deg frames map_match_edges\n"
      "# (|heading correction| between consecutive scans in one frame, odometry at stamp + "
      "offset)\n";
  for (const OffsetSweepRow& r : result.rows) {
    t += Format("%+.3f\t%d\t%.4f\t%.4f\t%d\t%d\n", r.offset_s, r.corrections.pairs,
                r.corrections.mean_abs_rad * kRadToDeg, r.corrections.rms_rad * kRadToDeg,
                r.summary.frames, r.summary.map_match_origin_edges);
  }
  const SweepBest& b = result.best;
  if (b.index < 0) {
    t += "# best: none (no pair of consecutive scans in one frame)\n";
  } else if (b.has_vertex) {
    t += Format("# best: %+.3f s (smallest mean); parabola vertex %+.3f s\n", b.offset_s,
                b.vertex_s);
  } else {
    t += Format(
        "# best: %+.3f s (smallest mean; at the end of the range or no curvature: widen "
        "the range)\n",
        b.offset_s);
  }
  return t;
}

}  // namespace atlas::replay
