#pragma once
// Generates an office building as large as asked for: a grid of corridor blocks whose
// corridors form loops of several sizes (every block is ringed by corridors; block widths and
// depths vary, and some neighbouring blocks are merged into one twice as long, so single-block
// and multi-block loops differ in length), each block holding two rows of rooms that open onto
// the corridors through doors, with clutter (boxes in room corners, cabinets along corridor
// walls). Also emits the route graph: corridor centreline nodes at every junction and in front
// of every door, a node just inside each door and one at each room's centre. Pure, seeded
// computation.

#include <cstdint>
#include <string>

#include "sim/world.h"

namespace atlas::sim {

struct BuildingOptions {
  int min_rooms = 24;           // the grid grows until it holds at least this many rooms
  double corridor_width = 2.0;  // m
  double door_width = 0.9;      // m
  double room_width_min = 3.5;  // m, along the corridor
  double room_width_max = 5.5;
  double room_depth_min = 4.0;  // m, away from the corridor
  double room_depth_max = 6.0;
  double block_width_min = 11.0;  // m, between two corridor walls
  double block_width_max = 24.0;
  double merged_block_probability = 0.3;  // two neighbouring blocks form one (bigger loops)
  int max_boxes_per_room = 2;             // clutter in the room corners away from the door
  double cabinets_per_10m = 0.6;          // clutter along corridor walls without doors

  std::string Validate() const;
};

// `options` must be valid. The same seed gives the same building.
World GenerateBuilding(const BuildingOptions& options, uint64_t seed);

}  // namespace atlas::sim
