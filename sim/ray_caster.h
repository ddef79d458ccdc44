#pragma once
// Ray casting against wall segments through a uniform grid (spatial index), so that the cost
// of one ray grows with the cells it crosses, not with the number of walls in the world.
//
// Each wall is listed in every cell its bounding box overlaps (exact for axis-aligned walls).
// A ray walks the cells in order (Amanatides & Woo, "A fast voxel traversal algorithm", 1987)
// and stops at the first cell whose nearest hit lies inside that cell. Glass walls are not
// hit: rays pass through them.

#include <vector>

#include "sim/world.h"

namespace atlas::sim {

struct RayHit {
  double range = 0.0;  // distance to the hit
  int wall = -1;       // index into the walls given to the caster, -1 = no hit
  bool hit() const { return wall >= 0; }
};

class RayCaster {
 public:
  // `cell_size` in metres; about the typical free-space width works well (1 m).
  explicit RayCaster(const std::vector<Wall>& walls, double cell_size = 1.0);

  // The first wall hit by the ray origin + t * direction, 0 < t <= max_range (direction is
  // normalised here). Returns a RayHit with wall = -1 if nothing within max_range.
  RayHit Cast(const Vec2& origin, const Vec2& direction, double max_range) const;
  // The same, but every wall tested brute force; the reference for tests and benchmarks.
  RayHit CastBruteForce(const Vec2& origin, const Vec2& direction, double max_range) const;

  const Wall& wall(int i) const { return walls_[i]; }
  int num_walls() const { return static_cast<int>(walls_.size()); }

 private:
  struct PackedWall {
    double ax, ay, dx, dy;  // start point and b - a
  };
  // Distance t along the unit ray (ox, oy) + t (ux, uy) to wall i, or +inf.
  double Intersect(int i, double ox, double oy, double ux, double uy) const;

  std::vector<Wall> walls_;
  std::vector<PackedWall> packed_;
  double cell_ = 1.0;
  Vec2 origin_ = Vec2::Zero();  // lower-left corner of the grid
  int nx_ = 0, ny_ = 0;
  std::vector<int> cell_start_;  // CSR: walls of cell c are cell_walls_[start[c] .. start[c+1])
  std::vector<int> cell_walls_;
};

}  // namespace atlas::sim
