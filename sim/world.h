#pragma once
// The simulator's 2D world: wall segments, plus a route graph of free-space waypoints that a
// robot can drive between in straight lines (corridor centrelines, doorways, room centres).
//
// Text format (docs/formats.md, "Simulator world"): line oriented, '#' starts a comment,
//   atlas-world 1                      first non-comment line: the format and its version
//   wall x1 y1 x2 y2                   a wall segment, metres
//   node id x y kind                   a waypoint; id = 0, 1, 2, ... in order; kind is
//                                      corridor | door | room
//   edge id1 id2                       the straight line between two nodes is free to drive
// ParseWorld works on streams; the caller owns files.

#include <iosfwd>
#include <string>
#include <vector>

#include "core/geometry/se2.h"

namespace atlas::sim {

struct Wall {
  Vec2 a = Vec2::Zero();
  Vec2 b = Vec2::Zero();
};

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

  int CountNodes(NodeKind kind) const;
};

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
