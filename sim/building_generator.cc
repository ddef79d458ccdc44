#include "sim/building_generator.h"

#include <algorithm>
#include <cmath>
#include <map>
#include <random>

namespace atlas::sim {
namespace {

struct Builder {
  const BuildingOptions& o;
  std::mt19937_64 rng;
  World world;

  double Uniform(double a, double b) { return std::uniform_real_distribution<double>(a, b)(rng); }

  void AddWall(double x0, double y0, double x1, double y1) {
    if (std::hypot(x1 - x0, y1 - y0) > 1e-6) world.walls.push_back({Vec2(x0, y0), Vec2(x1, y1)});
  }
  // Horizontal wall at y from x0 to x1 with door gaps centred at `doors`.
  void AddWallWithDoors(double y, double x0, double x1, std::vector<double> doors) {
    std::sort(doors.begin(), doors.end());
    double x = x0;
    for (double d : doors) {
      AddWall(x, y, d - 0.5 * o.door_width, y);
      x = d + 0.5 * o.door_width;
    }
    AddWall(x, y, x1, y);
  }
  void AddBox(double x0, double y0, double x1, double y1) {
    AddWall(x0, y0, x1, y0);
    AddWall(x1, y0, x1, y1);
    AddWall(x1, y1, x0, y1);
    AddWall(x0, y1, x0, y0);
  }
  int AddNode(double x, double y, NodeKind kind) {
    world.nodes.push_back({Vec2(x, y), kind});
    return static_cast<int>(world.nodes.size()) - 1;
  }
  // Splits [x0, x1] into rooms of roughly the configured width.
  std::vector<double> RoomCuts(double x0, double x1) {
    const double avg = 0.5 * (o.room_width_min + o.room_width_max);
    const int k = std::max(1, static_cast<int>(std::round((x1 - x0) / avg)));
    std::vector<double> cuts{x0};
    const double w = (x1 - x0) / k;
    const double jitter = std::min(0.25 * w, 0.5 * (o.room_width_max - o.room_width_min));
    for (int i = 1; i < k; ++i) cuts.push_back(x0 + i * w + Uniform(-jitter, jitter));
    cuts.push_back(x1);
    return cuts;
  }
  // Cabinets along a wall without doors: the wall at coordinate `c` across axis `vertical`
  // (x = c if vertical), from s0 to s1, the cabinets sticking out by `depth_sign` * depth.
  void AddCabinets(bool vertical, double c, double s0, double s1, double depth_sign) {
    const double keep_clear = 0.5 * o.corridor_width + 1.0;  // away from junctions
    const double len = s1 - s0 - 2.0 * keep_clear;
    if (len < 1.0) return;
    std::poisson_distribution<int> count(o.cabinets_per_10m * len / 10.0);
    const int n = count(rng);
    for (int i = 0; i < n; ++i) {
      const double s = s0 + keep_clear + Uniform(0.0, len - 0.8);
      const double size = Uniform(0.4, 0.8), depth = 0.3 * depth_sign;
      if (vertical) {
        AddBox(std::min(c, c + depth), s, std::max(c, c + depth), s + size);
      } else {
        AddBox(s, std::min(c, c + depth), s + size, std::max(c, c + depth));
      }
    }
  }
};

}  // namespace

std::string BuildingOptions::Validate() const {
  if (min_rooms < 1 || min_rooms > 100000) return "min_rooms must be in [1, 100000]";
  if (!(corridor_width >= 1.2 && corridor_width <= 10.0))
    return "corridor_width must be in [1.2, 10] m (a robot must pass)";
  if (!(door_width >= 0.7 && door_width <= room_width_min - 1.0))
    return "door_width must be at least 0.7 m and 1 m less than room_width_min";
  if (!(room_width_min >= 2.5 && room_width_max >= room_width_min && room_width_max <= 50.0))
    return "room widths must satisfy 2.5 <= room_width_min <= room_width_max <= 50 m";
  if (!(room_depth_min >= 3.0 && room_depth_max >= room_depth_min && room_depth_max <= 50.0))
    return "room depths must satisfy 3 <= room_depth_min <= room_depth_max <= 50 m";
  if (!(block_width_min >= room_width_min && block_width_max >= block_width_min &&
        block_width_max <= 500.0))
    return "block widths must satisfy room_width_min <= block_width_min <= block_width_max";
  if (!(merged_block_probability >= 0.0 && merged_block_probability <= 1.0))
    return "merged_block_probability must be in [0, 1]";
  if (max_boxes_per_room < 0 || max_boxes_per_room > 2) return "max_boxes_per_room: 0, 1 or 2";
  if (!(cabinets_per_10m >= 0.0 && cabinets_per_10m <= 5.0))
    return "cabinets_per_10m must be in [0, 5]";
  return "";
}

World GenerateBuilding(const BuildingOptions& o, uint64_t seed) {
  // Grow the grid of blocks until it holds enough rooms; the rooms per block are estimated.
  const double room_avg = 0.5 * (o.room_width_min + o.room_width_max);
  const double block_avg = 0.5 * (o.block_width_min + o.block_width_max);
  const int rooms_per_block = std::max(2, 2 * static_cast<int>(std::round(block_avg / room_avg)));
  int cols = 1, rows = 1;
  while (cols * rows * rooms_per_block < o.min_rooms) (cols <= rows ? cols : rows)++;

  for (;; (cols <= rows ? cols : rows)++) {
    Builder b{o, std::mt19937_64(seed), {}};
    const double w = o.corridor_width;
    std::vector<double> xs{0.0}, ys{0.0}, depth;
    for (int i = 0; i < cols; ++i)
      xs.push_back(xs.back() + w + b.Uniform(o.block_width_min, o.block_width_max));
    for (int j = 0; j < rows; ++j) {
      depth.push_back(b.Uniform(o.room_depth_min, o.room_depth_max));
      ys.push_back(ys.back() + w + 2.0 * depth.back());
    }
    // Outer walls, with cabinets along them.
    b.AddBox(xs.front() - 0.5 * w, ys.front() - 0.5 * w, xs.back() + 0.5 * w, ys.back() + 0.5 * w);
    for (int i = 0; i < cols; ++i) {
      b.AddCabinets(false, ys.front() - 0.5 * w, xs[i], xs[i + 1], 1.0);
      b.AddCabinets(false, ys.back() + 0.5 * w, xs[i], xs[i + 1], -1.0);
    }
    for (int j = 0; j < rows; ++j) {
      b.AddCabinets(true, xs.front() - 0.5 * w, ys[j], ys[j + 1], 1.0);
      b.AddCabinets(true, xs.back() + 0.5 * w, ys[j], ys[j + 1], -1.0);
    }

    // Vertical corridor pieces between corridors j and j + 1 at column line i; closing an inner
    // one merges two blocks into one twice as long, so that loops differ more in size.
    std::vector<std::vector<bool>> open(cols + 1, std::vector<bool>(rows, true));
    for (int j = 0; j < rows; ++j)
      for (int i = 1; i < cols; ++i)
        if (open[i - 1][j] && b.Uniform(0.0, 1.0) < o.merged_block_probability) open[i][j] = false;

    // Junction nodes, and the nodes on each horizontal corridor (by corridor index).
    std::vector<std::vector<int>> junction(cols + 1, std::vector<int>(rows + 1));
    std::vector<std::vector<int>> on_corridor(rows + 1);
    for (int j = 0; j <= rows; ++j)
      for (int i = 0; i <= cols; ++i) {
        junction[i][j] = b.AddNode(xs[i], ys[j], NodeKind::kCorridor);
        on_corridor[j].push_back(junction[i][j]);
      }

    int rooms = 0;
    for (int j = 0; j < rows; ++j) {
      for (int i = 0, end = 1; i < cols; i = end, end = i + 1) {
        while (!open[end][j]) ++end;
        const double xl = xs[i] + 0.5 * w, xr = xs[end] - 0.5 * w;
        const double yb = ys[j] + 0.5 * w, yt = ys[j + 1] - 0.5 * w, ym = 0.5 * (yb + yt);
        b.AddWall(xl, yb, xl, yt);
        b.AddWall(xr, yb, xr, yt);
        b.AddWall(xl, ym, xr, ym);
        if (i == 0) b.AddCabinets(true, xl, ys[j], ys[j + 1], -1.0);
        b.AddCabinets(true, xr, ys[j], ys[j + 1], 1.0);
        // Bottom row (doors at yb onto corridor j), top row (doors at yt onto corridor j+1).
        for (int side = 0; side < 2; ++side) {
          const double door_y = side == 0 ? yb : yt;
          const double inward = side == 0 ? 1.0 : -1.0;
          const int corridor = side == 0 ? j : j + 1;
          const std::vector<double> cuts = b.RoomCuts(xl, xr);
          std::vector<double> doors;
          for (size_t r = 0; r + 1 < cuts.size(); ++r) {
            const double rx0 = cuts[r], rx1 = cuts[r + 1];
            if (r > 0) b.AddWall(rx0, door_y, rx0, ym);
            const double margin = 0.3 + 0.5 * o.door_width;
            const double dx = b.Uniform(rx0 + margin, rx1 - margin);
            doors.push_back(dx);
            ++rooms;
            const int front = b.AddNode(dx, ys[corridor], NodeKind::kCorridor);
            on_corridor[corridor].push_back(front);
            const int door = b.AddNode(dx, door_y + inward * 0.6, NodeKind::kDoor);
            const int centre = b.AddNode(0.5 * (rx0 + rx1), 0.5 * (door_y + ym), NodeKind::kRoom);
            b.world.edges.push_back({front, door});
            b.world.edges.push_back({door, centre});
            // Boxes in the far corners (by the middle wall), away from door and centre.
            for (int corner = 0; corner < 2; ++corner) {
              if (corner >= o.max_boxes_per_room || b.Uniform(0.0, 1.0) < 0.35) continue;
              const double sx = b.Uniform(0.4, 0.9), sy = b.Uniform(0.4, 0.9);
              const double bx = corner == 0 ? rx0 : rx1 - sx;
              const double by = side == 0 ? ym - sy : ym;
              b.AddBox(bx, by, bx + sx, by + sy);
            }
          }
          b.AddWallWithDoors(door_y, xl, xr, doors);
        }
      }
    }
    if (rooms < o.min_rooms) continue;

    // Corridor edges: consecutive nodes along each horizontal and vertical corridor.
    for (int j = 0; j <= rows; ++j) {
      auto& ids = on_corridor[j];
      std::sort(ids.begin(), ids.end(), [&](int a, int c) {
        return b.world.nodes[a].position.x() < b.world.nodes[c].position.x();
      });
      for (size_t k = 0; k + 1 < ids.size(); ++k) b.world.edges.push_back({ids[k], ids[k + 1]});
    }
    for (int i = 0; i <= cols; ++i)
      for (int j = 0; j < rows; ++j)
        if (open[i][j]) b.world.edges.push_back({junction[i][j], junction[i][j + 1]});
    return std::move(b.world);
  }
}

}  // namespace atlas::sim
