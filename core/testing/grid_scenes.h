#pragma once
// Scenes for the grid tests and benchmarks: wall layouts (the simulator's walls) scanned by
// FakeWallScanner, and the grids and point sets made from them.

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <vector>

#include "core/grid/grid_options.h"
#include "core/grid/probability_grid.h"
#include "core/grid/range_inserter.h"
#include "core/testing/fake_wall_scanner.h"

namespace atlas {

// A closed 10 x 8 m room (times `scale`), origin at its centre, with an alcove, a pillar and
// an L-shaped counter, so that no placement but the true one fits it.
inline std::vector<sim::Wall> RoomWalls(double scale = 1.0) {
  std::vector<sim::Wall> w;
  auto box = [&w](double x0, double y0, double x1, double y1) {
    w.push_back({Vec2(x0, y0), Vec2(x1, y0)});
    w.push_back({Vec2(x1, y0), Vec2(x1, y1)});
    w.push_back({Vec2(x1, y1), Vec2(x0, y1)});
    w.push_back({Vec2(x0, y1), Vec2(x0, y0)});
  };
  w.push_back({Vec2(-5, -4), Vec2(5, -4)});
  w.push_back({Vec2(5, -4), Vec2(5, 1)});
  w.push_back({Vec2(5, 1), Vec2(6, 1)});  // alcove
  w.push_back({Vec2(6, 1), Vec2(6, 3)});
  w.push_back({Vec2(6, 3), Vec2(5, 3)});
  w.push_back({Vec2(5, 3), Vec2(5, 4)});
  w.push_back({Vec2(5, 4), Vec2(-5, 4)});
  w.push_back({Vec2(-5, 4), Vec2(-5, -4)});
  box(2.0, -2.5, 2.4, -2.1);                        // pillar
  w.push_back({Vec2(-4.0, 2.0), Vec2(-2.0, 2.0)});  // counter
  w.push_back({Vec2(-2.0, 2.0), Vec2(-2.0, 1.2)});
  for (sim::Wall& wall : w) {
    wall.a *= scale;
    wall.b *= scale;
  }
  return w;
}

// The distance from `p` to the nearest of `walls`.
inline double DistanceToWalls(const Vec2& p, const std::vector<sim::Wall>& walls) {
  double nearest = std::numeric_limits<double>::infinity();
  for (const sim::Wall& w : walls) {
    const Vec2 d = w.b - w.a;
    const double len2 = d.squaredNorm();
    const double t = len2 > 0 ? std::clamp((p - w.a).dot(d) / len2, 0.0, 1.0) : 0.0;
    nearest = std::min(nearest, (w.a + t * d - p).norm());
  }
  return nearest;
}

// Twelve poses spread over RoomWalls(scale)'s floor, as a robot crossing it would scan it.
inline std::vector<Pose2> RoomTour(double scale = 1.0) {
  std::vector<Pose2> poses;
  for (int i = 0; i < 12; ++i) {
    poses.push_back(Pose2{scale * (-3.5 + 0.6 * i), scale * 2.5 * std::sin(0.7 * i), 0.5 * i});
  }
  return poses;
}

// Two parallel walls 2 m apart along x from -100 to 100 m: nothing fixes x.
inline std::vector<sim::Wall> LongCorridorWalls() {
  return {{Vec2(-100, -1), Vec2(100, -1)}, {Vec2(-100, 1), Vec2(100, 1)}};
}

// Square posts of 0.2 m on a 1 m lattice over [-6, 6]^2: every 1 m shift looks alike.
inline std::vector<sim::Wall> PostLatticeWalls() {
  std::vector<sim::Wall> w;
  for (int i = -6; i <= 6; ++i) {
    for (int j = -6; j <= 6; ++j) {
      if (i == 0 && j == 0) continue;
      const double x = i - 0.1, y = j - 0.1;
      w.push_back({Vec2(x, y), Vec2(x + 0.2, y)});
      w.push_back({Vec2(x + 0.2, y), Vec2(x + 0.2, y + 0.2)});
      w.push_back({Vec2(x + 0.2, y + 0.2), Vec2(x, y + 0.2)});
      w.push_back({Vec2(x, y + 0.2), Vec2(x, y)});
    }
  }
  return w;
}

inline FakeLaserOptions FullCircleLaser(int beams = 361, double max_range = 30.0) {
  FakeLaserOptions o;
  o.beams = beams;
  o.fov = 2.0 * 3.14159265358979323846 * (beams - 1) / beams;
  o.max_range = max_range;
  o.range_sigma = 0.01;
  return o;
}

// A 180-degree laser looking ahead, as the simulator's and the logs' scanners.
inline FakeLaserOptions FrontLaser(int beams = 181, double max_range = 30.0) {
  FakeLaserOptions o;
  o.beams = beams;
  o.max_range = max_range;
  o.range_sigma = 0.01;
  return o;
}

// A grid of `walls` from scans at `poses` (world = submap frame).
inline ProbabilityGrid ScannedGrid(const std::vector<sim::Wall>& walls,
                                   const std::vector<Pose2>& poses, const GridOptions& options,
                                   uint64_t seed = 1) {
  FakeWallScanner scanner(walls, FullCircleLaser(), seed);
  ProbabilityGrid grid(options.grid);
  RangeInserter inserter(options.grid);
  RangeScan range;
  for (const Pose2& p : poses) {
    RangeScanFromLaser(scanner.Scan(p), p, options.range, &range);
    inserter.Insert(range, &grid);
  }
  return grid;
}

// The returns of one scan from `robot`, in the robot frame.
inline std::vector<Vec2> ScanPoints(const std::vector<sim::Wall>& walls, const Pose2& robot,
                                    const GridOptions& options, uint64_t seed = 2,
                                    const FakeLaserOptions& laser = FullCircleLaser()) {
  FakeWallScanner scanner(walls, laser, seed);
  RangeScan range;
  RangeScanFromLaser(scanner.Scan(robot), Pose2{}, options.range, &range);
  return range.returns;
}

// The occupied cells (probability >= 0.6) of a second submap of `walls` whose frame is
// `frame` in the walls' frame, built from RoomTour(scale) mirrored in x: the same place seen
// from other poses.
inline std::vector<Vec2> OtherSubmapPoints(const std::vector<sim::Wall>& walls, double scale,
                                           const Pose2& frame, const GridOptions& options) {
  std::vector<sim::Wall> moved;
  const RigidTransform to_frame(Inverse(frame));
  for (const sim::Wall& w : walls) moved.push_back({to_frame.Apply(w.a), to_frame.Apply(w.b)});
  std::vector<Pose2> tour;
  for (const Pose2& p : RoomTour(scale)) tour.push_back(Between(frame, Pose2{-p.x, p.y, -p.theta}));
  return OccupiedCellCenters(ScannedGrid(moved, tour, options, 5), 0.6);
}

}  // namespace atlas
