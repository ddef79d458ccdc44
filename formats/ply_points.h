#pragma once
// Point clouds as ASCII PLY (docs/formats.md, "PLY point cloud"), as CloudCompare, MeshLab,
// Open3D and PCL's PLY reader read them: a header naming one element "vertex" with the float
// properties x, y, z and the int property frame (the map-frame the point was kept by), then one
// line per point.

#include <span>
#include <string>
#include <string_view>
#include <vector>

#include "core/geometry/se2.h"

namespace atlas::formats {

struct PlyPoint {
  Vec2 p = Vec2::Zero();  // metres; z is 0
  int frame = 0;
};

// The file: "ply", "format ascii 1.0", "comment <comment>", the vertex element, "end_header",
// then "x y 0 frame" per point (metres with 3 decimals).
std::string FormatPlyPoints(std::span<const PlyPoint> points, std::string_view comment);

// Reads a file FormatPlyPoints writes: an ASCII PLY whose only element is "vertex" with the
// properties x y z frame, in that order; "" or "<source>:<line>: <what>" (a missing or
// different header line, a vertex line with a bad field, fewer or more vertex lines than the
// header's count).
std::string ParsePlyPoints(std::string_view text, const std::string& source,
                           std::vector<PlyPoint>* out);

}  // namespace atlas::formats
