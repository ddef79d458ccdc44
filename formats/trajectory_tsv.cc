#include "formats/trajectory_tsv.h"

#include "formats/pose_file.h"
#include "formats/text_rows.h"

namespace atlas::formats {

std::string ParseTrajectoryTsv(std::string_view text, const std::string& source,
                               std::vector<FramePoseRow>* out) {
  std::vector<std::pair<Time, int64_t>> stamps;
  std::string error =
      ForEachRow(text, source, 5, "timestamp frame x y theta",
                 [&](std::span<const std::string_view> f, int64_t line) {
                   FramePoseRow r;
                   r.line = line;
                   if (std::string e = StampField(f[0], 1, &r.stamp); !e.empty()) return e;
                   if (std::string e = FrameField(f[1], 2, false, &r.frame); !e.empty()) return e;
                   if (std::string e = PoseFields(f, 2, &r.pose); !e.empty()) return e;
                   out->push_back(r);
                   stamps.emplace_back(r.stamp, line);
                   return std::string();
                 });
  if (!error.empty()) return error;
  return RepeatedStamp(std::move(stamps), source);
}

std::string FormatTrajectoryTsv(std::span<const FramePoseRow> rows, std::string_view comment) {
  std::string text = "# " + std::string(comment) + "\n";
  text.reserve(rows.size() * 56 + text.size());
  for (const FramePoseRow& r : rows)
    AppendF(&text, "%.6f\t%d\t%.6f\t%.6f\t%.6f\n", ToSeconds(r.stamp), r.frame, r.pose.x, r.pose.y,
            r.pose.theta);
  return text;
}

}  // namespace atlas::formats
