#include "core/testing/fake_sonar_ring.h"

#include <cmath>
#include <numbers>

#include "core/localmap/line_model.h"
#include "core/sonar/sonar_geometry.h"

namespace atlas {

std::vector<SonarTransducer> FakeSonarRing(int count) {
  std::vector<SonarTransducer> ring;
  for (int i = 0; i < count; ++i) {
    const double a = WrapAngle((0.5 + i) * 2.0 * std::numbers::pi / count);
    SonarTransducer s;
    s.pose = Pose2{0.26 * std::cos(a), 0.26 * std::sin(a), a};
    s.max_range = 6.0;
    ring.push_back(s);
  }
  return ring;
}

std::vector<SonarTransducer> FakeSonarRing24() { return FakeSonarRing(24); }

SonarReading FireFakeSonarRing(const std::vector<sim::Wall>& walls,
                               const std::vector<SonarTransducer>& ring, const Pose2& robot,
                               double noise_sigma, std::mt19937_64& rng) {
  std::normal_distribution<double> n01;
  SonarReading reading;
  reading.returns.reserve(ring.size());
  for (int i = 0; i < static_cast<int>(ring.size()); ++i) {
    double best = kNoReturn;
    for (const sim::Wall& w : walls) {
      const double len = (w.b - w.a).norm();
      if (!(len > 0.0)) continue;
      const Vec2 d = (w.b - w.a) / len;
      const Vec2 line = LineThroughPoints(w.a, w.b);
      const SonarRangePrediction p = PredictSonarRange(robot, ring[i], line.x(), line.y());
      const double t = (p.foot - w.a).dot(d);
      if (!p.in_cone || t < 0.0 || t > len || p.range > ring[i].max_range) continue;
      best = std::min(best, p.range);
    }
    const float r =
        std::isfinite(best) ? static_cast<float>(best + noise_sigma * n01(rng)) : kNoReturn;
    reading.returns.push_back(SonarReturn{i, r});
  }
  return reading;
}

}  // namespace atlas
