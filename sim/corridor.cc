#include "sim/corridor.h"

namespace atlas::sim {

std::vector<Wall> CorridorWalls(double length, double width) {
  const double h = 0.5 * width;
  std::vector<Wall> w;
  // End walls.
  w.push_back({Vec2(-1.0, -h), Vec2(-1.0, h)});
  w.push_back({Vec2(length + 1.0, -h), Vec2(length + 1.0, h)});
  // Side walls with door recesses (0.3 m deep) every ~7 m, alternating sides.
  const double door = 1.0, depth = 0.3;
  for (int side = 0; side < 2; ++side) {
    const double y = side == 0 ? h : -h;
    const double out = side == 0 ? h + depth : -h - depth;
    double x = -1.0;
    double next_door = side == 0 ? 4.0 : 7.5;
    while (next_door + door < length) {
      w.push_back({Vec2(x, y), Vec2(next_door, y)});
      w.push_back({Vec2(next_door, y), Vec2(next_door, out)});
      w.push_back({Vec2(next_door, out), Vec2(next_door + door, out)});
      w.push_back({Vec2(next_door + door, out), Vec2(next_door + door, y)});
      x = next_door + door;
      next_door += 7.0;
    }
    w.push_back({Vec2(x, y), Vec2(length + 1.0, y)});
  }
  // A pillar (square, 0.4 m) standing off the north wall half way.
  const double px = 0.5 * length, py = h - 0.5;
  w.push_back({Vec2(px, py), Vec2(px + 0.4, py)});
  w.push_back({Vec2(px + 0.4, py), Vec2(px + 0.4, h)});
  w.push_back({Vec2(px, py), Vec2(px, h)});
  return w;
}

}  // namespace atlas::sim
