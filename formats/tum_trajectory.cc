#include "formats/tum_trajectory.h"

#include <cmath>

#include "formats/text_rows.h"

namespace atlas::formats {

std::string FormatTumTrajectory(std::span<const eval::TimedPose> poses, std::string_view comment) {
  std::string text = "# " + std::string(comment) + "\n";
  for (const eval::TimedPose& p : poses)
    AppendF(&text, "%.6f %.6f %.6f 0 0 0 %.9f %.9f\n", ToSeconds(p.stamp), p.pose.x, p.pose.y,
            std::sin(p.pose.theta / 2), std::cos(p.pose.theta / 2));
  return text;
}

std::string ParseTumTrajectory(std::string_view text, const std::string& source,
                               std::vector<eval::TimedPose>* out) {
  return ForEachRow(
      text, source, 8, "timestamp tx ty tz qx qy qz qw",
      [&](std::span<const std::string_view> f, int64_t) {
        eval::TimedPose p;
        if (std::string e = StampField(f[0], 1, &p.stamp); !e.empty()) return e;
        double v[7];
        for (size_t k = 0; k < 3; ++k)
          if (std::string e = CoordinateField(f[1 + k], 2 + k, false, &v[k]); !e.empty()) return e;
        for (size_t k = 3; k < 7; ++k)
          if (std::string e = NumberField(f[1 + k], 2 + k, &v[k]); !e.empty()) return e;
        const double qx = v[3], qy = v[4], qz = v[5], qw = v[6];
        const double norm = std::sqrt(qx * qx + qy * qy + qz * qz + qw * qw);
        if (std::abs(norm - 1.0) > 1e-6)
          return "the quaternion (fields 5-8) has norm " + std::to_string(norm) + ", not 1";
        if (std::abs(v[2]) > 1e-6 || std::abs(qx) > 1e-6 || std::abs(qy) > 1e-6)
          return std::string("the pose is not in the plane (tz, qx and qy must be 0)");
        p.pose = Pose2{v[0], v[1], WrapAngle(2 * std::atan2(qz, qw))};
        out->push_back(p);
        return std::string();
      });
}

}  // namespace atlas::formats
