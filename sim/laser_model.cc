#include "sim/laser_model.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>

namespace atlas::sim {
namespace {

// Distance along the unit ray from `origin` to the disc's near side, +inf if missed.
double RayToDisc(const Vec2& origin, const Vec2& unit, const Disc& disc) {
  const Vec2 w = disc.centre - origin;
  const double along = w.dot(unit), miss2 = w.squaredNorm() - along * along;
  const double r2 = disc.radius * disc.radius;
  if (miss2 > r2) return std::numeric_limits<double>::infinity();
  const double t = along - std::sqrt(r2 - miss2);
  return t > 0.0 ? t : std::numeric_limits<double>::infinity();
}

}  // namespace

std::string LaserOptions::Validate() const {
  if (beams < 2 || beams > 10000) return "laser beams must be in [2, 10000] (SICK: 181 or 361)";
  if (!(fov_deg > 0.0 && fov_deg <= 360.0)) return "laser fov_deg must be in (0, 360]";
  if (!(max_range > 0.1 && max_range <= 1000.0)) return "laser max_range must be in (0.1, 1000] m";
  if (!(range_sigma >= 0.0 && range_sigma < 1.0)) return "laser range_sigma must be in [0, 1) m";
  if (!(dropout_probability >= 0.0 && dropout_probability <= 1.0))
    return "laser dropout_probability must be in [0, 1]";
  if (!(rate_hz > 0.0 && rate_hz <= 1000.0)) return "laser rate_hz must be in (0, 1000]";
  return "";
}

LaserModel::LaserModel(const LaserOptions& options, uint64_t seed) : o_(options), noise_(seed) {
  const double fov = o_.fov_deg * std::numbers::pi / 180.0;
  const float angle_min = static_cast<float>(-0.5 * fov);
  const float increment = static_cast<float>(fov / (o_.beams - 1));
  for (int i = 0; i < o_.beams; ++i) {
    const double a = angle_min + i * static_cast<double>(increment);
    beam_dirs_.emplace_back(std::cos(a), std::sin(a));
  }
}

LaserScan LaserModel::Scan(const RayCaster& caster, const Pose2& robot, Time stamp,
                           std::span<const Disc> obstacles) {
  LaserScan scan;
  scan.stamp = stamp;
  const double fov = o_.fov_deg * std::numbers::pi / 180.0;
  scan.angle_min = static_cast<float>(-0.5 * fov);
  scan.angle_increment = static_cast<float>(fov / (o_.beams - 1));
  scan.max_range = static_cast<float>(o_.max_range);
  scan.sensor_pose = o_.mount;
  scan.ranges.resize(o_.beams);
  const Pose2 sensor = Compose(robot, o_.mount);
  const Vec2 origin(sensor.x, sensor.y);
  const double c = std::cos(sensor.theta), s = std::sin(sensor.theta);
  for (int i = 0; i < o_.beams; ++i) {
    const Vec2& b = beam_dirs_[i];
    const Vec2 dir(c * b.x() - s * b.y(), s * b.x() + c * b.y());
    const RayHit hit = caster.Cast(origin, dir, o_.max_range);
    double nearest = hit.hit() ? hit.range : std::numeric_limits<double>::infinity();
    for (const Disc& d : obstacles) nearest = std::min(nearest, RayToDisc(origin, dir, d));
    float range = kNoReturn;
    if (nearest <= o_.max_range) {
      const double r = nearest + o_.range_sigma * noise_.Normal();
      if (r < o_.max_range) range = static_cast<float>(std::max(0.0, r));
    }
    if (noise_.Chance(o_.dropout_probability)) range = kNoReturn;
    scan.ranges[i] = range;
  }
  return scan;
}

}  // namespace atlas::sim
