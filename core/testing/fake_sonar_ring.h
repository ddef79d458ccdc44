#pragma once
// A fake sonar ring for tests and benchmarks: the wide-beam tangent model exactly
// (core/sonar/sonar_geometry.h). A wall segment echoes when the perpendicular from the
// transducer meets it inside the segment with the normal inside the cone and within max_range;
// the nearest echo is reported (first return), plus Gaussian noise. No specular misses or
// multipath (the simulator, sim/sonar_model.h, has those). The walls are the simulator's
// (sim/world.h).

#include <random>
#include <vector>

#include "core/common/sensor_types.h"
#include "sim/world.h"

namespace atlas {

// `count` transducers evenly around a 0.26 m radius, the first at half a spacing from the
// heading, max range 6 m, 25 degree cones.
std::vector<SonarTransducer> FakeSonarRing(int count);
// 24 of them (B21-like).
std::vector<SonarTransducer> FakeSonarRing24();

// One reading with every transducer of `ring` fired from `robot`.
SonarReading FireFakeSonarRing(const std::vector<sim::Wall>& walls,
                               const std::vector<SonarTransducer>& ring, const Pose2& robot,
                               double noise_sigma, std::mt19937_64& rng);

}  // namespace atlas
