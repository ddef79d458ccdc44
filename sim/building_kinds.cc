#include "sim/building_kinds.h"

#include <algorithm>
#include <cmath>
#include <map>
#include <numbers>
#include <random>

#include "sim/building_generator.h"

namespace atlas::sim {
namespace {

constexpr double kPi = std::numbers::pi;

double DistanceToSegment(const Vec2& p, const Vec2& a, const Vec2& b) {
  const Vec2 d = b - a;
  const double len2 = d.squaredNorm();
  const double t = len2 > 0.0 ? std::clamp((p - a).dot(d) / len2, 0.0, 1.0) : 0.0;
  return (p - (a + t * d)).norm();
}

bool SegmentsCross(const Vec2& p, const Vec2& q, const Vec2& a, const Vec2& b) {
  auto cross = [](const Vec2& u, const Vec2& v) { return u.x() * v.y() - u.y() * v.x(); };
  const double d1 = cross(q - p, a - p), d2 = cross(q - p, b - p);
  const double d3 = cross(b - a, p - a), d4 = cross(b - a, q - a);
  return ((d1 > 0) != (d2 > 0)) && ((d3 > 0) != (d4 > 0));
}

// Free space as a union of shapes, by signed distance (negative inside).
struct Shape {
  enum Type { kCapsule, kBox, kDisc } type;
  Vec2 a = Vec2::Zero(), b = Vec2::Zero();  // capsule ends; box corners (axis-aligned); centre
  double r = 0.0;                           // capsule half width; disc radius

  double Distance(const Vec2& p) const {
    switch (type) {
      case kCapsule:
        return DistanceToSegment(p, a, b) - r;
      case kBox: {
        const Vec2 c = 0.5 * (a + b), h = 0.5 * (b - a).cwiseAbs();
        const Vec2 q = (p - c).cwiseAbs() - h;
        return q.cwiseMax(0.0).norm() + std::min(std::max(q.x(), q.y()), 0.0);
      }
      case kDisc:
        return (p - a).norm() - r;
    }
    return 0.0;
  }
};

// Joins segments sharing end points into polylines and merges runs of pieces that deviate less
// than `tolerance` from one straight wall.
std::vector<Wall> MergeSegments(const std::vector<Wall>& pieces, double tolerance) {
  std::map<std::pair<double, double>, std::vector<int>> at;
  auto key = [](const Vec2& p) { return std::make_pair(p.x(), p.y()); };
  for (int i = 0; i < static_cast<int>(pieces.size()); ++i) {
    at[key(pieces[i].a)].push_back(i);
    at[key(pieces[i].b)].push_back(i);
  }
  std::vector<bool> used(pieces.size(), false);
  std::vector<Wall> walls;
  for (size_t start = 0; start < pieces.size(); ++start) {
    if (used[start]) continue;
    used[start] = true;
    std::vector<Vec2> line{pieces[start].a, pieces[start].b};
    // Extend at the back, then at the front.
    for (int end = 0; end < 2; ++end) {
      while (true) {
        const Vec2 tip = end == 0 ? line.back() : line.front();
        int next = -1;
        for (int j : at[key(tip)])
          if (!used[j]) next = j;
        if (next < 0) break;
        used[next] = true;
        const Vec2 other = key(pieces[next].a) == key(tip) ? pieces[next].b : pieces[next].a;
        if (end == 0) {
          line.push_back(other);
        } else {
          line.insert(line.begin(), other);
        }
      }
    }
    size_t anchor = 0;
    while (anchor + 1 < line.size()) {
      size_t far = anchor + 1;
      while (far + 1 < line.size()) {
        bool straight = true;
        for (size_t k = anchor + 1; k <= far && straight; ++k)
          straight = DistanceToSegment(line[k], line[anchor], line[far + 1]) <= tolerance;
        if (!straight) break;
        ++far;
      }
      walls.push_back(Wall{line[anchor], line[far]});
      anchor = far;
    }
  }
  return walls;
}

// The boundary of the union of `shapes` (marching squares on the signed distance; every
// shape must lie inside the grid).
std::vector<Wall> CarveWalls(const std::vector<Shape>& shapes, double cell) {
  Bounds bounds;
  for (const Shape& s : shapes) {
    const Vec2 r(s.r + cell, s.r + cell);
    bounds.Extend(s.a.cwiseMin(s.b) - r);
    bounds.Extend(s.a.cwiseMax(s.b) + r);
  }
  if (shapes.empty()) return {};
  const Vec2 origin = bounds.min - Vec2(2 * cell, 2 * cell);
  const int nx = static_cast<int>(std::ceil((bounds.max.x() - origin.x()) / cell)) + 3;
  const int ny = static_cast<int>(std::ceil((bounds.max.y() - origin.y()) / cell)) + 3;
  auto point = [&](int i, int j) { return Vec2(origin.x() + i * cell, origin.y() + j * cell); };
  std::vector<double> f(static_cast<size_t>(nx + 1) * (ny + 1), 1e9);
  auto value = [&](int i, int j) -> double& { return f[static_cast<size_t>(j) * (nx + 1) + i]; };
  // Each shape only near itself: a vertex farther than 3 cells from a shape is not inside it, and
  // the shape cannot be the nearest to a vertex next to a boundary, so the signs and every
  // crossing are those of the minimum over all shapes.
  for (const Shape& s : shapes) {
    const Vec2 r(s.r + 3 * cell, s.r + 3 * cell);
    const Vec2 b = s.type == Shape::kDisc ? s.a : s.b;
    const Vec2 lo = (s.a.cwiseMin(b) - r - origin) / cell,
               hi = (s.a.cwiseMax(b) + r - origin) / cell;
    const int i0 = std::max(0, static_cast<int>(std::floor(lo.x())));
    const int j0 = std::max(0, static_cast<int>(std::floor(lo.y())));
    const int i1 = std::min(nx, static_cast<int>(std::ceil(hi.x())));
    const int j1 = std::min(ny, static_cast<int>(std::ceil(hi.y())));
    for (int j = j0; j <= j1; ++j)
      for (int i = i0; i <= i1; ++i) value(i, j) = std::min(value(i, j), s.Distance(point(i, j)));
  }
  // Never exactly zero, so that every crossing lies strictly inside an edge.
  for (double& d : f)
    if (d == 0.0) d = 1e-12;
  // The crossing on the edge from vertex (i0, j0) to (i1, j1), always in that order, so that
  // two cells sharing an edge compute the same point.
  auto crossing = [&](int i0, int j0, int i1, int j1) -> Vec2 {
    const double f0 = value(i0, j0), f1 = value(i1, j1);
    return point(i0, j0) + (f0 / (f0 - f1)) * (point(i1, j1) - point(i0, j0));
  };
  std::vector<Wall> pieces;
  for (int j = 0; j < ny; ++j)
    for (int i = 0; i < nx; ++i) {
      const bool free[4] = {value(i, j) < 0, value(i + 1, j) < 0, value(i + 1, j + 1) < 0,
                            value(i, j + 1) < 0};
      const int c = free[0] | free[1] << 1 | free[2] << 2 | free[3] << 3;
      if (c == 0 || c == 15) continue;
      const Vec2 e[4] = {free[0] != free[1] ? crossing(i, j, i + 1, j) : Vec2::Zero(),
                         free[1] != free[2] ? crossing(i + 1, j, i + 1, j + 1) : Vec2::Zero(),
                         free[3] != free[2] ? crossing(i, j + 1, i + 1, j + 1) : Vec2::Zero(),
                         free[0] != free[3] ? crossing(i, j, i, j + 1) : Vec2::Zero()};
      auto add = [&](int p, int q) { pieces.push_back(Wall{e[p], e[q]}); };
      const double centre =
          0.25 * (value(i, j) + value(i + 1, j) + value(i + 1, j + 1) + value(i, j + 1));
      switch (c) {
        case 1:
        case 14:
          add(3, 0);
          break;
        case 2:
        case 13:
          add(0, 1);
          break;
        case 3:
        case 12:
          add(3, 1);
          break;
        case 4:
        case 11:
          add(1, 2);
          break;
        case 6:
        case 9:
          add(0, 2);
          break;
        case 7:
        case 8:
          add(2, 3);
          break;
        case 5:
          if (centre < 0)
            add(0, 1), add(2, 3);
          else
            add(3, 0), add(1, 2);
          break;
        case 10:
          if (centre < 0)
            add(3, 0), add(1, 2);
          else
            add(0, 1), add(2, 3);
          break;
      }
    }
  return MergeSegments(pieces, 0.002);
}

struct KindBuilder {
  std::mt19937_64 rng;
  World world;

  double Uniform(double a, double b) { return std::uniform_real_distribution<double>(a, b)(rng); }
  bool Chance(double p) { return Uniform(0.0, 1.0) < p; }

  int AddNode(const Vec2& p, NodeKind kind) {
    world.nodes.push_back({p, kind});
    return static_cast<int>(world.nodes.size()) - 1;
  }
  void AddEdge(int a, int b) { world.edges.push_back({a, b}); }
  // A closed polygon of walls.
  void AddPolygon(const std::vector<Vec2>& corners) {
    for (size_t k = 0; k < corners.size(); ++k)
      world.walls.push_back({corners[k], corners[(k + 1) % corners.size()]});
  }
  // A rectangle of size w x h centred at c, turned by `angle`.
  std::vector<Vec2> Rectangle(const Vec2& c, double w, double h, double angle) const {
    const Vec2 u(std::cos(angle), std::sin(angle)), v(-u.y(), u.x());
    return {c - 0.5 * w * u - 0.5 * h * v, c + 0.5 * w * u - 0.5 * h * v,
            c + 0.5 * w * u + 0.5 * h * v, c - 0.5 * w * u + 0.5 * h * v};
  }
  // True if every corner keeps `route_clearance` from every route edge and no edge of the
  // polygon crosses a route edge or comes within `wall_clearance` of a wall's end or body.
  bool Clear(const std::vector<Vec2>& poly, double route_clearance, double wall_clearance) const {
    for (const RouteEdge& e : world.edges) {
      const Vec2 &a = world.nodes[e.from].position, &b = world.nodes[e.to].position;
      for (size_t k = 0; k < poly.size(); ++k) {
        if (DistanceToSegment(poly[k], a, b) < route_clearance) return false;
        if (SegmentsCross(poly[k], poly[(k + 1) % poly.size()], a, b)) return false;
      }
    }
    for (const Wall& w : world.walls)
      for (size_t k = 0; k < poly.size(); ++k) {
        const Vec2 &p = poly[k], &q = poly[(k + 1) % poly.size()];
        if (DistanceToSegment(p, w.a, w.b) < wall_clearance || SegmentsCross(p, q, w.a, w.b) ||
            DistanceToSegment(w.a, p, q) < wall_clearance)
          return false;
      }
    return true;
  }
  // Adds the polygons (one piece of furniture) if all are clear; true if added.
  bool AddIfClear(const std::vector<std::vector<Vec2>>& polys, double route_clearance) {
    for (const auto& p : polys)
      if (!Clear(p, route_clearance, 0.05)) return false;
    for (const auto& p : polys) AddPolygon(p);
    return true;
  }
};

// The default office generator, its rooms fewer so that the extra furniture, glass or people
// are met often.
World SmallOffice(uint64_t seed) {
  BuildingOptions o;
  o.min_rooms = 16;
  return GenerateBuilding(o, seed);
}

World Curved(uint64_t seed) {
  KindBuilder k{std::mt19937_64(seed), {}};
  const double ax = k.Uniform(15.0, 22.0), by = k.Uniform(10.0, 14.0), width = 2.4;
  auto on_ring = [&](double phi) { return Vec2(ax * std::cos(phi), by * std::sin(phi)); };
  std::vector<Shape> shapes;
  const int dense = 200;
  for (int i = 0; i < dense; ++i)
    shapes.push_back({Shape::kCapsule, on_ring(2 * kPi * i / dense),
                      on_ring(2 * kPi * (i + 1) / dense), 0.5 * width});
  const double hall_radius = k.Uniform(4.0, 5.5);
  shapes.push_back({Shape::kDisc, Vec2::Zero(), Vec2::Zero(), hall_radius});
  // Two diagonal corridors through the hall, neither along an axis nor along the other.
  const double chord1 = k.Uniform(0.35, 1.2), chord2 = chord1 + k.Uniform(1.0, 2.0);
  std::vector<double> chord_angles{chord1, chord1 + kPi, chord2, chord2 + kPi};
  for (int c = 0; c < 2; ++c)
    shapes.push_back({Shape::kCapsule, on_ring(chord_angles[2 * c]),
                      on_ring(chord_angles[2 * c + 1]), 0.5 * k.Uniform(1.8, 2.4)});
  k.world.walls = CarveWalls(shapes, 0.1);

  // Ring nodes about every 3 m, and one at each diagonal's end.
  std::vector<std::pair<double, bool>> phis;
  const int n = static_cast<int>(std::round(2 * kPi * std::sqrt(0.5 * (ax * ax + by * by)) / 3.0));
  for (int i = 0; i < n; ++i) phis.push_back({2 * kPi * i / n, false});
  for (double a : chord_angles) {
    const double w = std::fmod(a, 2 * kPi);
    std::erase_if(phis, [&](const auto& p) {
      return !p.second && std::abs(std::remainder(p.first - w, 2 * kPi)) < kPi / n;
    });
    phis.push_back({w, true});
  }
  std::sort(phis.begin(), phis.end());
  const int centre = k.AddNode(Vec2::Zero(), NodeKind::kRoom);
  std::vector<int> ring;
  for (const auto& [phi, chord_end] : phis) {
    ring.push_back(k.AddNode(on_ring(phi), NodeKind::kCorridor));
    if (chord_end) k.AddEdge(ring.back(), centre);
  }
  for (size_t i = 0; i < ring.size(); ++i) k.AddEdge(ring[i], ring[(i + 1) % ring.size()]);
  return std::move(k.world);
}

World Clutter(uint64_t seed) {
  KindBuilder k{std::mt19937_64(seed ^ 0x636c7574746572ULL), SmallOffice(seed)};
  const std::vector<RouteNode> nodes = k.world.nodes;
  auto posts = [&](const std::vector<Vec2>& corners, double size) {
    std::vector<std::vector<Vec2>> legs;
    for (const Vec2& c : corners) legs.push_back(k.Rectangle(c, size, size, 0.0));
    return legs;
  };
  for (const RouteNode& room : nodes) {
    if (room.kind != NodeKind::kRoom) continue;
    // A table on four legs with chairs (four legs each) beside it.
    for (int tries = 0; tries < 20; ++tries) {
      const double dir = k.Uniform(0.0, 2 * kPi), turn = k.Uniform(0.0, kPi);
      const Vec2 c = room.position + k.Uniform(1.0, 1.8) * Vec2(std::cos(dir), std::sin(dir));
      const std::vector<Vec2> top = k.Rectangle(c, 1.2, 0.7, turn);
      std::vector<Vec2> legs_at = k.Rectangle(c, 1.1, 0.6, turn);
      const Vec2 u(std::cos(turn), std::sin(turn)), v(-u.y(), u.x());
      for (double side : {-1.0, 1.0}) {
        if (k.Chance(0.3)) continue;
        for (const Vec2& p : k.Rectangle(c + side * 0.65 * v + k.Uniform(-0.3, 0.3) * u, 0.38, 0.38,
                                         turn + k.Uniform(-0.4, 0.4)))
          legs_at.push_back(p);
      }
      if (k.AddIfClear(posts(legs_at, 0.04), 0.45)) break;
    }
    // A shelf and a furniture block.
    for (int item = 0; item < 2; ++item)
      for (int tries = 0; tries < 20; ++tries) {
        const double dir = k.Uniform(0.0, 2 * kPi);
        const Vec2 c = room.position + k.Uniform(1.2, 2.4) * Vec2(std::cos(dir), std::sin(dir));
        const double turn = 0.5 * kPi * std::floor(k.Uniform(0.0, 4.0));
        const auto poly = item == 0 ? k.Rectangle(c, k.Uniform(1.0, 2.0), 0.35, turn)
                                    : k.Rectangle(c, k.Uniform(0.5, 1.0), k.Uniform(0.5, 1.0),
                                                  k.Uniform(0.0, kPi));
        if (k.AddIfClear({poly}, 0.45)) break;
      }
  }
  return std::move(k.world);
}

World Glass(uint64_t seed) {
  KindBuilder k{std::mt19937_64(seed ^ 0x676c617373ULL), SmallOffice(seed)};
  for (Wall& w : k.world.walls)
    if ((w.b - w.a).norm() > 1.2 && k.Chance(0.35)) w.glass = true;
  return std::move(k.world);
}

World Corridor(uint64_t seed) {
  KindBuilder k{std::mt19937_64(seed), {}};
  const double w = 2.0, t = 0.2, pitch = k.Uniform(3.5, 4.5), room_depth = 4.0;
  const int rooms_per_side = static_cast<int>(std::round(k.Uniform(60.0, 90.0) / pitch));
  const int middle = rooms_per_side / 2;  // a cross corridor in place of this room
  const double first = 0.5 * w + t;       // where the first room begins
  const double length = first + rooms_per_side * pitch + 0.5 * w;
  const double top = w + 2 * (room_depth + t) + t;  // centreline of the second corridor
  std::vector<Shape> shapes;
  auto box = [&](double x0, double y0, double x1, double y1) {
    shapes.push_back({Shape::kBox, Vec2(x0, y0), Vec2(x1, y1), 0.0});
  };
  box(-0.5 * w, -0.5 * w, length + 0.5 * w, 0.5 * w);
  box(-0.5 * w, top - 0.5 * w, length + 0.5 * w, top + 0.5 * w);
  const double middle_x = first + middle * pitch + 0.5 * (pitch - t);
  for (double x : {0.0, middle_x, length}) box(x - 0.5 * w, 0.0, x + 0.5 * w, top);
  std::vector<int> on_corridor[2];
  for (int side = 0; side < 2; ++side) {
    const double cy = side == 0 ? 0.0 : top, inward = side == 0 ? 1.0 : -1.0;
    const double wall_in = cy + inward * 0.5 * w, wall_out = cy - inward * 0.5 * w;
    for (int r = 0; r < rooms_per_side; ++r) {
      const double x0 = first + r * pitch, x1 = x0 + pitch - t, door_x = x0 + 0.3 * pitch;
      // The same alcove opposite every room (overlapping the corridor, so that no seam is
      // left between the two shapes).
      const double in_corridor = wall_out + inward * 0.1, back = wall_out - inward * 0.8;
      box(x0 + 0.25 * pitch, std::min(in_corridor, back), x0 + 0.25 * pitch + 1.4,
          std::max(in_corridor, back));
      if (r == middle) continue;
      const double far = wall_in + inward * (t + room_depth);
      box(x0, std::min(wall_in + inward * t, far), x1, std::max(wall_in + inward * t, far));
      box(door_x - 0.45, std::min(wall_in - inward * 0.1, wall_in + inward * 2 * t), door_x + 0.45,
          std::max(wall_in - inward * 0.1, wall_in + inward * 2 * t));
      if (r % 2 == 1) continue;  // the route enters every other room
      const int front = k.AddNode(Vec2(door_x, cy), NodeKind::kCorridor);
      const int door = k.AddNode(Vec2(door_x, wall_in + inward * (t + 0.6)), NodeKind::kDoor);
      const int centre = k.AddNode(Vec2(0.5 * (x0 + x1), 0.5 * (wall_in + far)), NodeKind::kRoom);
      k.AddEdge(front, door);
      k.AddEdge(door, centre);
      on_corridor[side].push_back(front);
    }
  }
  k.world.walls = CarveWalls(shapes, 0.1);
  for (double x : {0.0, middle_x, length}) {
    const int a = k.AddNode(Vec2(x, 0.0), NodeKind::kCorridor);
    const int b = k.AddNode(Vec2(x, top), NodeKind::kCorridor);
    k.AddEdge(a, b);
    on_corridor[0].push_back(a);
    on_corridor[1].push_back(b);
  }
  for (auto& ids : on_corridor) {
    std::sort(ids.begin(), ids.end(), [&](int a, int b) {
      return k.world.nodes[a].position.x() < k.world.nodes[b].position.x();
    });
    for (size_t i = 0; i + 1 < ids.size(); ++i) k.AddEdge(ids[i], ids[i + 1]);
  }
  return std::move(k.world);
}

World Hall(uint64_t seed) {
  KindBuilder k{std::mt19937_64(seed), {}};
  const double spacing = 10.0;
  const int nx = static_cast<int>(k.Uniform(7.0, 9.0)), ny = static_cast<int>(k.Uniform(4.0, 6.0));
  const double width = (nx - 1) * spacing + 2 * 5.0, height = (ny - 1) * spacing + 2 * 5.0;
  k.AddPolygon(
      {Vec2(-5, -5), Vec2(width - 5, -5), Vec2(width - 5, height - 5), Vec2(-5, height - 5)});
  std::vector<int> id(nx * ny);
  for (int j = 0; j < ny; ++j)
    for (int i = 0; i < nx; ++i)
      id[j * nx + i] = k.AddNode(Vec2(i * spacing, j * spacing), NodeKind::kCorridor);
  for (int j = 0; j < ny; ++j)
    for (int i = 0; i < nx; ++i) {
      if (i + 1 < nx) k.AddEdge(id[j * nx + i], id[j * nx + i + 1]);
      if (j + 1 < ny) k.AddEdge(id[j * nx + i], id[(j + 1) * nx + i]);
    }
  // A few pillars in the middle of grid cells, some boxes along the walls.
  for (int j = 0; j + 1 < ny; ++j)
    for (int i = 0; i + 1 < nx; ++i)
      if (k.Chance(0.3))
        k.AddIfClear({k.Rectangle(Vec2((i + 0.5) * spacing, (j + 0.5) * spacing), 0.6, 0.6, 0.0)},
                     1.0);
  for (int n = 0; n < 8; ++n) {
    const bool along_x = k.Chance(0.5);
    const Vec2 c = along_x ? Vec2(k.Uniform(0.0, width - 10), k.Chance(0.5) ? -4.6 : height - 5.4)
                           : Vec2(k.Chance(0.5) ? -4.6 : width - 5.4, k.Uniform(0.0, height - 10));
    k.AddIfClear({k.Rectangle(c, along_x ? 1.5 : 0.6, along_x ? 0.6 : 1.5, 0.0)}, 1.0);
  }
  return std::move(k.world);
}

World Campus(uint64_t seed) {
  KindBuilder k{std::mt19937_64(seed), {}};
  const double spacing = 45.0;
  const int n = 4;
  std::vector<int> id(n * n);
  for (int j = 0; j < n; ++j)
    for (int i = 0; i < n; ++i) {
      const Vec2 jitter(k.Uniform(-4.0, 4.0), k.Uniform(-4.0, 4.0));
      id[j * n + i] = k.AddNode(Vec2(i * spacing, j * spacing) + jitter, NodeKind::kCorridor);
    }
  for (int j = 0; j < n; ++j)
    for (int i = 0; i < n; ++i) {
      if (i + 1 < n) k.AddEdge(id[j * n + i], id[j * n + i + 1]);
      if (j + 1 < n) k.AddEdge(id[j * n + i], id[(j + 1) * n + i]);
    }
  // Buildings in most blocks between the paths, some turned; a few outside the grid.
  for (int j = -1; j < n; ++j)
    for (int i = -1; i < n; ++i) {
      const bool inside = i >= 0 && j >= 0 && i + 1 < n && j + 1 < n;
      if (!k.Chance(inside ? 0.75 : 0.25)) continue;
      for (int tries = 0; tries < 10; ++tries) {
        const Vec2 c((i + 0.5) * spacing + k.Uniform(-6, 6),
                     (j + 0.5) * spacing + k.Uniform(-6, 6));
        const double turn = k.Chance(0.6) ? 0.0 : k.Uniform(0.0, 0.5 * kPi);
        if (k.AddIfClear({k.Rectangle(c, k.Uniform(10, 28), k.Uniform(10, 28), turn)}, 5.0)) break;
      }
    }
  // Trees and lamp posts beside the paths.
  const int edges = static_cast<int>(k.world.edges.size());
  for (int e = 0; e < edges; ++e) {
    const Vec2 a = k.world.nodes[k.world.edges[e].from].position;
    const Vec2 b = k.world.nodes[k.world.edges[e].to].position;
    const Vec2 side = Vec2(a.y() - b.y(), b.x() - a.x()).normalized();
    for (int t = 0; t < 3; ++t) {
      const Vec2 c = a + k.Uniform(0.15, 0.85) * (b - a) + (k.Chance(0.5) ? 3.0 : -3.0) * side;
      const double s = k.Uniform(0.15, 0.5);
      k.AddIfClear({k.Rectangle(c, s, s, k.Uniform(0.0, kPi))}, 1.5);
    }
  }
  return std::move(k.world);
}

World People(uint64_t seed) {
  KindBuilder k{std::mt19937_64(seed ^ 0x70656f706c65ULL), SmallOffice(seed)};
  // Each walks to and fro along a straight stretch of corridor between two corridor nodes.
  std::vector<std::pair<int, int>> stretches;
  const auto& nodes = k.world.nodes;
  for (size_t a = 0; a < nodes.size(); ++a)
    for (size_t b = a + 1; b < nodes.size(); ++b) {
      if (nodes[a].kind != NodeKind::kCorridor || nodes[b].kind != NodeKind::kCorridor) continue;
      const Vec2 d = nodes[b].position - nodes[a].position;
      if (d.norm() < 6.0 || d.norm() > 25.0 || (std::abs(d.x()) > 1e-9 && std::abs(d.y()) > 1e-9))
        continue;
      bool blocked = false;
      for (const Wall& w : k.world.walls)
        blocked = blocked || SegmentsCross(nodes[a].position, nodes[b].position, w.a, w.b) ||
                  DistanceToSegment(w.a, nodes[a].position, nodes[b].position) < 0.5 ||
                  DistanceToSegment(w.b, nodes[a].position, nodes[b].position) < 0.5;
      if (!blocked) stretches.push_back({static_cast<int>(a), static_cast<int>(b)});
    }
  for (int p = 0; p < 6 && !stretches.empty(); ++p) {
    const auto [a, b] =
        stretches[std::uniform_int_distribution<size_t>(0, stretches.size() - 1)(k.rng)];
    const Vec2 d = (nodes[b].position - nodes[a].position).normalized();
    const Vec2 side = k.Uniform(-0.4, 0.4) * Vec2(-d.y(), d.x());
    k.world.people.push_back(
        {nodes[a].position + side, nodes[b].position + side, k.Uniform(0.8, 1.4)});
  }
  return std::move(k.world);
}

}  // namespace

const std::vector<BuildingKind>& AllBuildingKinds() {
  static const std::vector<BuildingKind> kinds{BuildingKind::kOffice,   BuildingKind::kCurved,
                                               BuildingKind::kClutter,  BuildingKind::kGlass,
                                               BuildingKind::kCorridor, BuildingKind::kHall,
                                               BuildingKind::kCampus,   BuildingKind::kPeople};
  return kinds;
}

const char* ToString(BuildingKind kind) {
  switch (kind) {
    case BuildingKind::kOffice:
      return "office";
    case BuildingKind::kCurved:
      return "curved";
    case BuildingKind::kClutter:
      return "clutter";
    case BuildingKind::kGlass:
      return "glass";
    case BuildingKind::kCorridor:
      return "corridor";
    case BuildingKind::kHall:
      return "hall";
    case BuildingKind::kCampus:
      return "campus";
    case BuildingKind::kPeople:
      return "people";
  }
  return "?";
}

bool ParseBuildingKind(std::string_view name, BuildingKind* kind) {
  for (BuildingKind k : AllBuildingKinds())
    if (name == ToString(k)) {
      *kind = k;
      return true;
    }
  return false;
}

double KindLaserMaxRange(BuildingKind kind) { return kind == BuildingKind::kCampus ? 80.0 : 30.0; }

bool KindIsClosed(BuildingKind kind) { return kind != BuildingKind::kCampus; }

World GenerateKind(BuildingKind kind, uint64_t seed) {
  switch (kind) {
    case BuildingKind::kOffice:
      return GenerateBuilding(BuildingOptions{}, seed);
    case BuildingKind::kCurved:
      return Curved(seed);
    case BuildingKind::kClutter:
      return Clutter(seed);
    case BuildingKind::kGlass:
      return Glass(seed);
    case BuildingKind::kCorridor:
      return Corridor(seed);
    case BuildingKind::kHall:
      return Hall(seed);
    case BuildingKind::kCampus:
      return Campus(seed);
    case BuildingKind::kPeople:
      return People(seed);
  }
  return {};
}

}  // namespace atlas::sim
