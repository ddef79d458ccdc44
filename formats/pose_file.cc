#include "formats/pose_file.h"

#include <algorithm>
#include <cstdio>

#include "formats/text_rows.h"

namespace atlas::formats {

std::string RepeatedStamp(std::vector<std::pair<Time, int64_t>> stamps, const std::string& source) {
  std::stable_sort(stamps.begin(), stamps.end(),
                   [](const auto& a, const auto& b) { return a.first < b.first; });
  std::string error;
  int64_t worst_line = 0;
  for (size_t i = 1; i < stamps.size(); ++i) {
    if (stamps[i].first != stamps[i - 1].first) continue;
    const int64_t later = std::max(stamps[i].second, stamps[i - 1].second);
    if (!error.empty() && later >= worst_line) continue;
    worst_line = later;
    char buf[64];
    std::snprintf(buf, sizeof buf, "%.6f", ToSeconds(stamps[i].first));
    error = source + ":" + std::to_string(later) + ": timestamp " + buf + " repeats line " +
            std::to_string(std::min(stamps[i].second, stamps[i - 1].second)) +
            " (one pose per stamp: remove one of the two rows)";
  }
  return error;
}

PoseRows ParsePoseRows(std::string_view text, const std::string& source) {
  PoseRows out;
  out.error = ForEachRow(text, source, 4, "timestamp x y theta",
                         [&](std::span<const std::string_view> f, int64_t line) {
                           eval::TimedPose p;
                           if (std::string e = StampField(f[0], 1, &p.stamp); !e.empty()) return e;
                           if (std::string e = PoseFields(f, 1, &p.pose); !e.empty()) return e;
                           out.poses.push_back(p);
                           out.lines.push_back(line);
                           return std::string();
                         });
  if (out.error.empty()) {
    std::vector<std::pair<Time, int64_t>> stamps;
    stamps.reserve(out.poses.size());
    for (size_t i = 0; i < out.poses.size(); ++i)
      stamps.emplace_back(out.poses[i].stamp, out.lines[i]);
    out.error = RepeatedStamp(std::move(stamps), source);
  }
  return out;
}

std::string FormatPoseRows(std::span<const eval::TimedPose> poses, std::string_view comment) {
  std::string text;
  text.reserve(poses.size() * 48 + comment.size() + 4);
  size_t pos = 0;
  while (pos <= comment.size()) {
    size_t end = comment.find('\n', pos);
    if (end == std::string_view::npos) end = comment.size();
    text += "# ";
    text += comment.substr(pos, end - pos);
    text += '\n';
    pos = end + 1;
  }
  for (const eval::TimedPose& p : poses)
    AppendF(&text, "%.6f\t%.6f\t%.6f\t%.6f\n", ToSeconds(p.stamp), p.pose.x, p.pose.y,
            p.pose.theta);
  return text;
}

}  // namespace atlas::formats
