#pragma once
// The simulated corridor of the evaluation tools' Monte Carlo runs: 20 m x 2.4 m
// (sim::CorridorWalls), the robot driving back and forth along its centre 40 times, weaving
// +-0.25 m between waypoints 3 m apart, at most 0.6 m/s; odometry at 50 Hz, range data at every
// kScanEvery-th odometry step (10 Hz).

#include <cstdint>
#include <vector>

#include "core/geometry/se2.h"
#include "sim/ray_caster.h"
#include "sim/route.h"

namespace atlas::mc {

inline constexpr double kOdometryDt = 0.02;  // seconds
inline constexpr int kScanEvery = 5;

std::vector<sim::Wall> CorridorWalls();
std::vector<Vec2> CorridorWaypoints();
sim::MotionOptions CorridorMotion();

// The seeds of a run's noise generators: wheel odometry and laser.
inline uint64_t OdometrySeed(uint64_t seed) { return seed * 7919 + 1; }
inline uint64_t LaserSeed(uint64_t seed) { return seed * 104729 + 3; }

}  // namespace atlas::mc
