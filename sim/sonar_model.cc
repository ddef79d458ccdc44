#include "sim/sonar_model.h"

#include <cmath>
#include <numbers>

namespace atlas::sim {
namespace {

constexpr double kDeg = std::numbers::pi / 180.0;

}  // namespace

std::vector<SonarTransducer> P3dxSonarRing() {
  // Pioneer 3 operations manual: x mm, y mm, heading deg.
  const double t[16][3] = {
      {69, 136, 90},     {114, 119, 50},     {148, 78, 30},     {166, 27, 10},
      {166, -27, -10},   {148, -78, -30},    {114, -119, -50},  {69, -136, -90},
      {-157, -136, -90}, {-203, -119, -130}, {-237, -78, -150}, {-255, -27, -170},
      {-255, 27, 170},   {-237, 78, 150},    {-203, 119, 130},  {-157, 136, 90}};
  std::vector<SonarTransducer> ring;
  for (const auto& r : t) {
    SonarTransducer s;
    s.pose = Pose2{r[0] * 1e-3, r[1] * 1e-3, WrapAngle(r[2] * kDeg)};
    ring.push_back(s);
  }
  return ring;
}

std::vector<SonarTransducer> B21SonarRing() {
  std::vector<SonarTransducer> ring;
  for (int i = 0; i < 24; ++i) {
    const double a = WrapAngle((7.5 + 15.0 * i) * kDeg);
    SonarTransducer s;
    s.pose = Pose2{0.26 * std::cos(a), 0.26 * std::sin(a), a};
    s.max_range = 6.0;
    ring.push_back(s);
  }
  return ring;
}

std::string SonarOptions::Validate() const {
  if (ring.empty() || ring.size() > 64) return "sonar ring must have 1 to 64 transducers";
  for (const SonarTransducer& t : ring)
    if (!(t.beam_width > 0.0 && t.beam_width < std::numbers::pi && t.max_range > 0.0))
      return "sonar transducer beam_width must be in (0, pi) and max_range positive";
  if (rays_per_cone < 1 || rays_per_cone > 101) return "sonar rays_per_cone must be in [1, 101]";
  if (!(critical_incidence_deg > 0.0 && critical_incidence_deg < 90.0))
    return "sonar critical_incidence_deg must be in (0, 90)";
  if (!(multipath_probability >= 0.0 && multipath_probability <= 1.0))
    return "sonar multipath_probability must be in [0, 1]";
  if (!(range_sigma >= 0.0) || !(range_sigma_per_m >= 0.0)) return "sonar noise must be >= 0";
  if (!(reading_hz > 0.0 && reading_hz <= 1000.0)) return "sonar reading_hz must be in (0, 1000]";
  if (!(firings_per_second > 0.0 && firings_per_second <= 10000.0))
    return "sonar firings_per_second must be in (0, 10000]";
  return "";
}

SonarModel::SonarModel(const SonarOptions& options, uint64_t seed) : o_(options), noise_(seed) {}

float SonarModel::Fire(const RayCaster& caster, const Pose2& robot, int index) {
  const SonarTransducer& t = o_.ring[index];
  const Pose2 sensor = Compose(robot, t.pose);
  const Vec2 origin(sensor.x, sensor.y);
  const double critical_cos = std::cos(o_.critical_incidence_deg * kDeg);
  double best = std::numeric_limits<double>::infinity();
  RayHit central;
  Vec2 central_dir = Vec2::Zero();
  const int n = o_.rays_per_cone;
  for (int k = 0; k < n; ++k) {
    const double offset = n == 1 ? 0.0 : t.beam_width * (static_cast<double>(k) / (n - 1) - 0.5);
    const Vec2 u(std::cos(sensor.theta + offset), std::sin(sensor.theta + offset));
    const RayHit hit = caster.Cast(origin, u, t.max_range);
    if (k == n / 2) {
      central = hit;
      central_dir = u;
    }
    if (!hit.hit()) continue;
    const Wall& w = caster.wall(hit.wall);
    const Vec2 d = (w.b - w.a).normalized();
    const double cos_incidence = std::abs(u.x() * d.y() - u.y() * d.x());  // |u . normal|
    if (cos_incidence >= critical_cos) best = std::min(best, hit.range);
  }
  if (std::isfinite(best)) {
    const double r = best + (o_.range_sigma + o_.range_sigma_per_m * best) * noise_.Normal();
    return static_cast<float>(std::clamp(r, 0.0, t.max_range));
  }
  // Specular miss: maybe one more bounce.
  if (!central.hit() || !noise_.Chance(o_.multipath_probability)) return kNoReturn;
  const Wall& w = caster.wall(central.wall);
  const Vec2 d = (w.b - w.a).normalized();
  const Vec2 normal(-d.y(), d.x());
  const Vec2 reflected = central_dir - 2.0 * central_dir.dot(normal) * normal;
  const Vec2 p1 = origin + central.range * central_dir;
  const RayHit second = caster.Cast(p1 + 1e-6 * reflected, reflected, t.max_range * 2.0);
  if (!second.hit()) return kNoReturn;
  const Vec2 p2 = p1 + second.range * reflected;
  const double half_path = 0.5 * (central.range + second.range + (p2 - origin).norm());
  if (half_path >= t.max_range) return kNoReturn;
  return static_cast<float>(half_path);
}

SonarReading SonarModel::Read(const RayCaster& caster, const Pose2& robot, Time stamp) {
  SonarReading reading;
  reading.stamp = stamp;
  firing_credit_ += o_.firings_per_second / o_.reading_hz;
  const int ring = static_cast<int>(o_.ring.size());
  while (firing_credit_ >= 1.0) {
    firing_credit_ -= 1.0;
    reading.returns.push_back(SonarReturn{next_, Fire(caster, robot, next_)});
    next_ = (next_ + 1) % ring;
  }
  return reading;
}

}  // namespace atlas::sim
