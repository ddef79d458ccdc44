#include "tools/monte_carlo/corridor.h"

#include "sim/corridor.h"

namespace atlas::mc {

std::vector<sim::Wall> CorridorWalls() { return sim::CorridorWalls(20.0, 2.4); }

std::vector<Vec2> CorridorWaypoints() {
  std::vector<Vec2> w;
  for (int lap = 0; lap < 40; ++lap) {
    for (int i = 0; i <= 6; ++i) {
      const int k = lap % 2 == 0 ? i : 6 - i;
      w.push_back(Vec2(1.0 + 3.0 * k, (k % 2 == 0 ? 0.25 : -0.25)));
    }
  }
  return w;
}

sim::MotionOptions CorridorMotion() {
  sim::MotionOptions m;
  m.max_speed = 0.6;
  return m;
}

}  // namespace atlas::mc
