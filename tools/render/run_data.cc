#include "tools/render/run_data.h"

#include <algorithm>
#include <cmath>
#include <fstream>

#include "formats/pose_file.h"
#include "formats/text_rows.h"
#include "logs/carmen/carmen_line.h"
#include "sim/simulation.h"

namespace atlas::draw {

Pose2 InterpolateTruth(const std::vector<TruthSample>& truth, Time stamp) {
  auto it = std::lower_bound(truth.begin(), truth.end(), stamp,
                             [](const TruthSample& s, Time t) { return s.stamp < t; });
  if (it == truth.begin()) return truth.front().pose;
  if (it == truth.end()) return truth.back().pose;
  const TruthSample& b = *it;
  const TruthSample& a = *(it - 1);
  const double span = ToSeconds(b.stamp - a.stamp);
  const double f = span > 0 ? ToSeconds(stamp - a.stamp) / span : 0.0;
  return InterpolatePose(a.pose, b.pose, f);
}

std::vector<Vec2> ScanPoints(const RunScan& scan, const Pose2& laser_pose) {
  std::vector<Vec2> points;
  points.reserve(scan.ranges.size());
  for (size_t i = 0; i < scan.ranges.size(); ++i) {
    if (!IsReturn(scan.ranges[i])) continue;
    const double a = laser_pose.theta + scan.angle_min + i * scan.angle_increment;
    points.emplace_back(laser_pose.x + scan.ranges[i] * std::cos(a),
                        laser_pose.y + scan.ranges[i] * std::sin(a));
  }
  return points;
}

std::string ReadRun(const std::string& dir, const RunReadOptions& options, RunData* run) {
  *run = RunData{};
  const std::string world_path = dir + "/world.txt";
  {
    std::ifstream in(world_path);
    if (!in)
      return "cannot open " + world_path + " (is " + dir + " an atlas-sim output directory?)";
    sim::WorldParseResult parsed = sim::ParseWorld(in, world_path);
    if (!parsed.ok()) return parsed.error;
    run->world = std::move(parsed.world);
  }
  {
    const std::string path = dir + "/truth.tsv";
    const formats::TextFile text = formats::ReadTextFile(path);
    if (!text.error.empty())
      return text.error + (text.missing ? " (is " + dir + " an atlas-sim output directory?)" : "");
    formats::PoseRows rows = formats::ParsePoseRows(text.text, path);
    if (!rows.error.empty()) return rows.error;
    if (rows.poses.empty()) return path + ": no rows (atlas-sim writes one per odometry step)";
    std::stable_sort(rows.poses.begin(), rows.poses.end(),
                     [](const auto& a, const auto& b) { return a.stamp < b.stamp; });
    for (const eval::TimedPose& p : rows.poses) run->truth.push_back({p.stamp, p.pose});
  }
  std::string line;
  const std::string log_path = dir + "/run.clf";
  std::ifstream in(log_path);
  if (!in) return "cannot open " + log_path;
  const long max_scans = std::max(1L, options.max_scans);
  std::vector<long> kept_index;
  long n = 0;
  while (std::getline(in, line)) {
    ++n;
    // Every line is parsed, kept or not, so that a damaged line is reported, not skipped.
    const carmen::ParsedLine p = carmen::ParseLine(line);
    if (!p.ok()) return log_path + ":" + std::to_string(n) + ": " + p.reason;
    if (p.message == "SONAR") ++run->sonar_lines;
    if (p.kind == carmen::LineKind::kLaser && p.message == "FLASER") {
      const long index = run->total_scans++;
      if (index % run->scan_stride != 0) continue;
    }
    if (p.kind == carmen::LineKind::kOdometry) {
      run->odometry.push_back(
          OdometrySample{FromSeconds(p.odometry.ipc_timestamp), p.odometry.pose});
    } else if (p.kind == carmen::LineKind::kLaser && p.message == "FLASER" && p.laser.laser_pose &&
               p.laser.odometry_pose) {
      RunScan s;
      s.stamp = FromSeconds(p.laser.ipc_timestamp);
      s.laser_in_odometry = *p.laser.laser_pose;
      s.robot_odometry = *p.laser.odometry_pose;
      s.angle_min = p.laser.start_angle;
      s.angle_increment = p.laser.angular_resolution;
      s.ranges = p.laser.ranges;
      for (float& r : s.ranges)
        if (r >= 80.0f) r = kNoReturn;
      run->scans.push_back(std::move(s));
      kept_index.push_back(run->total_scans - 1);
      if (static_cast<long>(run->scans.size()) > 2 * max_scans) {
        run->scan_stride *= 2;
        std::vector<RunScan> thinned;
        std::vector<long> thinned_index;
        for (size_t k = 0; k < run->scans.size(); ++k)
          if (kept_index[k] % run->scan_stride == 0) {
            thinned.push_back(std::move(run->scans[k]));
            thinned_index.push_back(kept_index[k]);
          }
        run->scans = std::move(thinned);
        kept_index = std::move(thinned_index);
      }
    }
  }
  if (in.bad()) return "read error in " + log_path;
  if (run->odometry.empty() && run->total_scans == 0)
    return log_path + ": no ODOM or FLASER lines (atlas-sim writes both)";
  return "";
}

}  // namespace atlas::draw
