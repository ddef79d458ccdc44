#pragma once
// A small hand-made world for tests and evaluations: a straight corridor of `length` x `width`
// metres along +x from the origin with closed ends, door recesses (0.3 m deep, 1 m wide) every
// 7 m on alternating sides, and a 0.4 m pillar standing off the north wall half way, giving
// lines in three directions. Walls only, no route graph.

#include <vector>

#include "sim/world.h"

namespace atlas::sim {

std::vector<Wall> CorridorWalls(double length = 30.0, double width = 2.4);

}  // namespace atlas::sim
