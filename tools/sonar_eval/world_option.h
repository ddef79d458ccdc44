#pragma once
// The --world of atlas-sonar-eval's atlas and assoc modes: atlas-sim's building (rooms and
// corridor loops, layout from the seed) or the alcove loop (alcove_loop_world.h).

#include <string>

#include "sim/world.h"
#include "tools/sonar_eval/alcove_loop_world.h"

namespace atlas::sonar_eval {

// `name` "building" (at least `rooms` rooms, layout from `seed`) or "alcoves" (`loop`): fills
// `world` and returns "", else says what is wrong.
std::string SelectWorld(const std::string& name, int seed, int rooms, const AlcoveLoopOptions& loop,
                        sim::World* world);

}  // namespace atlas::sonar_eval
