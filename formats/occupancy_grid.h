#pragma once
// Occupancy grids as ROS map_server reads and writes them (docs/formats.md, "Occupancy grid"):
// an 8-bit binary PGM (P5) image and a YAML file beside it,
//
//   image: NAME.pgm
//   mode: trinary
//   resolution: R        # metres per pixel
//   origin: [x, y, yaw]  # the pose of the lower-left pixel's lower-left corner
//   negate: 0
//   occupied_thresh: 0.65
//   free_thresh: 0.196
//
// Pixels are written as map_saver writes them: occupied 0 (black), free 254 (white), unknown
// 205 (grey); the image's first row is the top of the map (largest y). With negate 0 map_server
// reads p = (255 - pixel) / 255: occupied above occupied_thresh, free below free_thresh.

#include <cstdint>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include "core/geometry/se2.h"

namespace atlas::formats {

enum class Occupancy : int8_t { kUnknown = -1, kFree = 0, kOccupied = 100 };

struct OccupancyGrid {
  int width = 0;   // cells along x
  int height = 0;  // cells along y
  double resolution = 0.05;
  Vec2 origin = Vec2::Zero();    // the corner of cell (0, 0), the smallest x and y
  std::vector<Occupancy> cells;  // row-major from the bottom row (y = origin.y) up

  Occupancy At(int ix, int iy) const { return cells[static_cast<size_t>(iy) * width + ix]; }
  // The cell holding `p`; false outside the grid.
  bool CellOf(const Vec2& p, int* ix, int* iy) const;
};

// A grid of `resolution` covering `points` with `margin` metres around them, every cell holding
// a point occupied, the others unknown. An empty grid (0 x 0) without points.
OccupancyGrid OccupiedCellsGrid(std::span<const Vec2> points, double resolution, double margin);

// The PGM image (binary P5, maxval 255, a comment line) and the YAML text naming `image`.
std::string FormatPgm(const OccupancyGrid& grid, std::string_view comment);
std::string FormatMapYaml(const OccupancyGrid& grid, std::string_view image);

// What a PGM's header says, and its pixels (rows top first).
struct PgmImage {
  int width = 0;
  int height = 0;
  int maxval = 0;
  std::vector<uint8_t> pixels;
};
// Reads a binary 8-bit PGM (P5, maxval 1..255, '#' comments in the header); "" or
// "<source>: <what>" (another magic number, a bad header field, fewer or more pixel bytes than
// width x height).
std::string ParsePgm(std::string_view bytes, const std::string& source, PgmImage* out);

// The keys of a map_server YAML file. Every key above is required but "mode" (trinary, scale
// or raw; map_server's default trinary).
struct MapYaml {
  std::string image;
  std::string mode = "trinary";
  double resolution = 0.0;
  Pose2 origin;
  int negate = 0;
  double occupied_thresh = 0.0;
  double free_thresh = 0.0;
};
// "" or "<source>:<line>: <what>" (a line not "key: value", an unknown or repeated key, a bad
// value), or "<source>: no key K".
std::string ParseMapYaml(std::string_view text, const std::string& source, MapYaml* out);

}  // namespace atlas::formats
