#pragma once
// The simulator's 2D world: wall segments, plus a route graph of free-space waypoints that a
// robot can drive between in straight lines (corridor centrelines, doorways, room centres).
//
// Text format (docs/formats.md, "Simulator world"): line oriented, '#' starts a comment,
//   atlas-world 1                      first non-comment line: the format and its version
//   wall x1 y1 x2 y2 [glass]           a wall segment, metres; 'glass': the laser sees through
//   node id x y kind                   a waypoint; id = 0, 1, 2, ... in order; kind is
//                                      corridor | door | room
//   edge id1 id2                       the straight line between two nodes is free to drive
//   person x1 y1 x2 y2 speed           someone walking to and fro between two points (m/s)
// ParseWorld works on streams; the caller owns files.

#include <array>
#include <iosfwd>
#include <string>
#include <vector>

#include "core/geometry/se2.h"

namespace atlas::sim {

struct Wall {
  Vec2 a = Vec2::Zero();
  Vec2 b = Vec2::Zero();
  bool glass = false;  // gives the laser (and the sonar) no return: rays pass through
};

// A person walking to and fro between `a` and `b` at `speed` m/s, at `a` at time 0. Seen by
// the sensors as two legs; never part of the walls (a map's truth).
struct Person {
  Vec2 a = Vec2::Zero();
  Vec2 b = Vec2::Zero();
  double speed = 1.0;
};
struct Disc {
  Vec2 centre = Vec2::Zero();
  double radius = 0.0;
};
// The person's two legs at `t` seconds: discs of 6 cm radius 0.2 m apart across the walking
// direction, swinging 0.15 m along it with a 0.7 m stride.
std::array<Disc, 2> PersonLegs(const Person& person, double t);

enum class NodeKind { kCorridor, kDoor, kRoom };
const char* ToString(NodeKind kind);

struct RouteNode {
  Vec2 position = Vec2::Zero();
  NodeKind kind = NodeKind::kCorridor;
};

struct RouteEdge {
  int from = 0;
  int to = 0;
};

struct World {
  std::vector<Wall> walls;
  std::vector<RouteNode> nodes;
  std::vector<RouteEdge> edges;
  std::vector<Person> people;

  int CountNodes(NodeKind kind) const;
};

// Each node's neighbours along the route edges.
std::vector<std::vector<int>> RouteAdjacency(const World& world);
// How many nodes the route graph reaches from node `from` (itself included).
int CountReachableNodes(const World& world, int from);

struct Bounds {
  Vec2 min = Vec2::Zero();
  Vec2 max = Vec2::Zero();
  bool empty = true;
  void Extend(const Vec2& p);
};
Bounds WorldBounds(const World& world);

struct WorldParseResult {
  World world;
  std::string error;  // empty on success, else "<source>:<line>: what is wrong"
  bool ok() const { return error.empty(); }
};

// Reads the text format. `source` names the input in error messages.
WorldParseResult ParseWorld(std::istream& in, const std::string& source);
// Writes the text format; ParseWorld reads it back exactly (coordinates printed round-trip).
void WriteWorld(std::ostream& out, const World& world);

}  // namespace atlas::sim
