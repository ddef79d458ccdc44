#include "tools/sonar_eval/alcove_loop_world.h"

#include <algorithm>
#include <cmath>

namespace atlas::sonar_eval {
namespace {

bool In(double v, double lo, double hi) { return v >= lo && v <= hi; }

// One side of the outer wall, from p to q (counter-clockwise, so outward is to the right),
// with its alcoves.
void AddOuterSide(const AlcoveLoopOptions& o, const Vec2& p, const Vec2& q, sim::World* w) {
  const double len = (q - p).norm();
  const Vec2 u = (q - p) / len;
  const Vec2 out(u.y(), -u.x());
  const double first = o.corridor_width + o.corner_clearance;
  const double usable = len - 2.0 * first;
  std::vector<double> starts;
  if (usable >= o.alcove_width) {
    const int n = static_cast<int>(std::floor((usable - o.alcove_width) / o.period)) + 1;
    const double span = (n - 1) * o.period + o.alcove_width;
    for (int k = 0; k < n; ++k) starts.push_back(first + 0.5 * (usable - span) + k * o.period);
  }
  double s = 0.0;
  for (const double a : starts) {
    const double b = a + o.alcove_width;
    const Vec2 pa = p + a * u, pb = p + b * u;
    w->walls.push_back({p + s * u, pa});
    w->walls.push_back({pa, pa + o.alcove_depth * out});
    w->walls.push_back({pa + o.alcove_depth * out, pb + o.alcove_depth * out});
    w->walls.push_back({pb + o.alcove_depth * out, pb});
    s = b;
  }
  w->walls.push_back({p + s * u, q});
}

}  // namespace

std::string AlcoveLoopOptions::Validate() const {
  if (!In(corridor_width, 0.8, 10.0)) return "corridor_width must lie in [0.8, 10] m";
  if (!In(length, 2.0 * corridor_width + 1.0, 1000.0) ||
      !In(width, 2.0 * corridor_width + 1.0, 1000.0)) {
    return "length and width must exceed twice the corridor width by 1 m (at most 1000 m)";
  }
  if (!In(alcove_width, 0.3, 10.0)) return "alcove_width must lie in [0.3, 10] m";
  if (!In(alcove_depth, 0.2, 10.0)) return "alcove_depth must lie in [0.2, 10] m";
  if (!In(period, alcove_width + 0.3, 100.0))
    return "period must lie in [alcove_width + 0.3, 100] m";
  if (!In(corner_clearance, 0.0, 100.0)) return "corner_clearance must lie in [0, 100] m";
  if (!In(node_spacing, 0.5, 100.0)) return "node_spacing must lie in [0.5, 100] m";
  return "";
}

sim::World AlcoveLoopWorld(const AlcoveLoopOptions& o) {
  sim::World w;
  const double l = o.length, h = o.width, c = o.corridor_width;
  const Vec2 outer[4] = {Vec2(0, 0), Vec2(l, 0), Vec2(l, h), Vec2(0, h)};
  for (int i = 0; i < 4; ++i) AddOuterSide(o, outer[i], outer[(i + 1) % 4], &w);
  const Vec2 inner[4] = {Vec2(c, c), Vec2(l - c, c), Vec2(l - c, h - c), Vec2(c, h - c)};
  for (int i = 0; i < 4; ++i) w.walls.push_back({inner[i], inner[(i + 1) % 4]});
  const double m = 0.5 * c;
  const Vec2 ring[4] = {Vec2(m, m), Vec2(l - m, m), Vec2(l - m, h - m), Vec2(m, h - m)};
  for (int i = 0; i < 4; ++i) {
    const Vec2 a = ring[i], b = ring[(i + 1) % 4];
    const int n = std::max(1, static_cast<int>(std::ceil((b - a).norm() / o.node_spacing)));
    for (int k = 0; k < n; ++k)
      w.nodes.push_back({a + (b - a) * (static_cast<double>(k) / n), sim::NodeKind::kCorridor});
  }
  const int count = static_cast<int>(w.nodes.size());
  for (int i = 0; i < count; ++i) w.edges.push_back({i, (i + 1) % count});
  return w;
}

}  // namespace atlas::sonar_eval
