#pragma once
// Building kinds that a map made of straight lines describes badly (issue 32, "Generalisation
// discipline"), each generated from a seed with a route graph whose loops bring the robot back
// to places it has seen:
//   office     the default generator (building_generator.h), unchanged
//   curved     an elliptical ring corridor (arcs as short segments) crossed by two diagonal
//              corridors through a round hall
//   clutter    an office whose rooms hold tables and chairs (legs: small posts), shelves and
//              furniture blocks
//   glass      an office where a share of the walls are glass (no laser return)
//   corridor   long corridors with identical alcoves and doors at a fixed pitch
//   hall       a hall wider than the laser's range, a few pillars, a grid of paths
//   campus     sparse buildings in open space, 30-80 m apart; not closed
//   people     an office with people walking along the corridors (moving, not in the walls)
// Curved and corridor walls are the boundary of a union of free-space shapes (marching squares
// on its signed distance, collinear pieces merged), so junctions at any angle are exact.
// Pure, seeded computation.

#include <cstdint>
#include <string>
#include <string_view>
#include <vector>

#include "sim/world.h"

namespace atlas::sim {

enum class BuildingKind { kOffice, kCurved, kClutter, kGlass, kCorridor, kHall, kCampus, kPeople };

// Every kind, in the order above.
const std::vector<BuildingKind>& AllBuildingKinds();
const char* ToString(BuildingKind kind);
// False if `name` names no kind.
bool ParseBuildingKind(std::string_view name, BuildingKind* kind);

// The laser's maximum range a kind is meant to be seen with (m): 80 for the campus (an LMS in
// centimetre mode), 30 otherwise (the simulator's default).
double KindLaserMaxRange(BuildingKind kind);
// Whether the walls enclose every route node (false for the campus).
bool KindIsClosed(BuildingKind kind);

// The same kind and seed give the same world. kOffice is GenerateBuilding with the default
// BuildingOptions.
World GenerateKind(BuildingKind kind, uint64_t seed);

}  // namespace atlas::sim
