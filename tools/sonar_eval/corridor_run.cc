#include "tools/sonar_eval/corridor_run.h"

#include <string>

#include "tools/monte_carlo/corridor.h"

namespace atlas::sonar_eval {
namespace {

WheelOdometryNoiseOptions Wheel() {
  WheelOdometryNoiseOptions w;
  w.left_scale_error = w.right_scale_error = w.track_width_error = 0.0;
  return w;
}

sim::LaserOptions Laser() {
  sim::LaserOptions l;
  l.beams = 361;
  return l;
}

}  // namespace

sim::SonarOptions SonarOptionsFor(int ring) {
  sim::SonarOptions s;
  s.ring = ring == 16 ? sim::P3dxSonarRing() : sim::B21SonarRing();
  return s;
}

cli::ToolModeOption RingOption(int ring) {
  return {"--ring", "16|24",
          "transducers of the sonar ring (default " + std::to_string(ring) + ")"};
}

CorridorRun::CorridorRun(uint64_t seed, int ring)
    : walls(mc::CorridorWalls()),
      caster(walls),
      wheel(Wheel()),
      laser(Laser()),
      sonar(SonarOptionsFor(ring)),
      odometry(wheel, mc::OdometrySeed(seed)),
      scanner(laser, mc::LaserSeed(seed)),
      ring_model(sonar, seed * 15485863 + 5),
      follower(mc::CorridorMotion(), mc::CorridorWaypoints()) {}

}  // namespace atlas::sonar_eval
