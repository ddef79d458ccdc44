#include "sim/world.h"

#include <charconv>
#include <cmath>
#include <istream>
#include <numbers>
#include <ostream>
#include <sstream>

#include "core/common/parse_number.h"

namespace atlas::sim {
namespace {

std::vector<std::string_view> SplitWords(std::string_view line) {
  std::vector<std::string_view> words;
  size_t i = 0;
  while (i < line.size()) {
    while (i < line.size() && (line[i] == ' ' || line[i] == '\t' || line[i] == '\r')) ++i;
    size_t j = i;
    while (j < line.size() && line[j] != ' ' && line[j] != '\t' && line[j] != '\r') ++j;
    if (j > i) words.push_back(line.substr(i, j - i));
    i = j;
  }
  return words;
}

// Shortest text that reads back to the same double.
std::string Num(double v) {
  char buf[32];
  const auto r = std::to_chars(buf, buf + sizeof(buf), v);
  return std::string(buf, r.ptr);
}

}  // namespace

const char* ToString(NodeKind kind) {
  switch (kind) {
    case NodeKind::kCorridor:
      return "corridor";
    case NodeKind::kDoor:
      return "door";
    case NodeKind::kRoom:
      return "room";
  }
  return "?";
}

std::array<Disc, 2> PersonLegs(const Person& p, double t) {
  constexpr double kLegRadius = 0.06, kStride = 0.7;
  const Vec2 path = p.b - p.a;
  const double length = path.norm();
  if (length < 1e-9) return {Disc{p.a, kLegRadius}, Disc{p.a, kLegRadius}};
  const double s = std::fmod(p.speed * std::max(t, 0.0), 2.0 * length);
  const Vec2 u = path / length;
  const Vec2 centre = p.a + (s < length ? s : 2.0 * length - s) * u;
  const Vec2 forward = s < length ? u : Vec2(-u), side(-u.y(), u.x());
  const double swing = 0.15 * std::sin(std::numbers::pi * s / kStride);
  return {Disc{centre + 0.1 * side + swing * forward, kLegRadius},
          Disc{centre - 0.1 * side - swing * forward, kLegRadius}};
}

int World::CountNodes(NodeKind kind) const {
  int n = 0;
  for (const RouteNode& node : nodes) n += node.kind == kind;
  return n;
}

std::vector<std::vector<int>> RouteAdjacency(const World& world) {
  std::vector<std::vector<int>> adjacent(world.nodes.size());
  for (const RouteEdge& e : world.edges) {
    adjacent[e.from].push_back(e.to);
    adjacent[e.to].push_back(e.from);
  }
  return adjacent;
}

int CountReachableNodes(const World& world, int from) {
  const auto adjacent = RouteAdjacency(world);
  std::vector<bool> seen(world.nodes.size(), false);
  std::vector<int> open{from};
  seen[from] = true;
  int reached = 1;
  while (!open.empty()) {
    const int n = open.back();
    open.pop_back();
    for (int m : adjacent[n])
      if (!seen[m]) seen[m] = true, ++reached, open.push_back(m);
  }
  return reached;
}

void Bounds::Extend(const Vec2& p) {
  if (empty) {
    min = max = p;
    empty = false;
  } else {
    min = min.cwiseMin(p);
    max = max.cwiseMax(p);
  }
}

Bounds WorldBounds(const World& world) {
  Bounds b;
  for (const Wall& w : world.walls) {
    b.Extend(w.a);
    b.Extend(w.b);
  }
  for (const RouteNode& n : world.nodes) b.Extend(n.position);
  return b;
}

WorldParseResult ParseWorld(std::istream& in, const std::string& source) {
  WorldParseResult result;
  World& world = result.world;
  std::string line;
  int line_no = 0;
  bool have_header = false;
  auto fail = [&](const std::string& what) {
    result.world = World{};
    result.error = source + ":" + std::to_string(line_no) + ": " + what;
    return result;
  };
  while (std::getline(in, line)) {
    ++line_no;
    const size_t hash = line.find('#');
    const auto words = SplitWords(std::string_view(line).substr(0, hash));
    if (words.empty()) continue;
    const std::string_view key = words[0];
    if (!have_header) {
      if (key != "atlas-world" || words.size() != 2 || words[1] != "1")
        return fail("expected the header line 'atlas-world 1' (is this an atlas world file?)");
      have_header = true;
      continue;
    }
    if (key == "wall") {
      double v[4];
      if (words.size() != 5 && !(words.size() == 6 && words[5] == "glass"))
        return fail("'wall' needs 4 numbers: x1 y1 x2 y2, then optionally 'glass'");
      for (int i = 0; i < 4; ++i)
        if (!ParseNumber(words[i + 1], &v[i]))
          return fail("'wall': '" + std::string(words[i + 1]) + "' is not a finite number");
      world.walls.push_back(Wall{Vec2(v[0], v[1]), Vec2(v[2], v[3]), words.size() == 6});
    } else if (key == "person") {
      double v[5];
      if (words.size() != 6) return fail("'person' needs 5 numbers: x1 y1 x2 y2 speed");
      for (int i = 0; i < 5; ++i)
        if (!ParseNumber(words[i + 1], &v[i]))
          return fail("'person': '" + std::string(words[i + 1]) + "' is not a finite number");
      if (!(v[4] > 0.0 && v[4] <= 5.0)) return fail("'person': speed must be in (0, 5] m/s");
      world.people.push_back(Person{Vec2(v[0], v[1]), Vec2(v[2], v[3]), v[4]});
    } else if (key == "node") {
      int id;
      double x, y;
      if (words.size() != 5) return fail("'node' needs: id x y kind");
      if (!ParseInteger(words[1], &id)) return fail("'node': id is not an integer");
      if (id != static_cast<int>(world.nodes.size()))
        return fail("'node': expected id " + std::to_string(world.nodes.size()) +
                    " (ids count up from 0 in order)");
      if (!ParseNumber(words[2], &x) || !ParseNumber(words[3], &y))
        return fail("'node': x y must be finite numbers");
      RouteNode node{Vec2(x, y), NodeKind::kCorridor};
      if (words[4] == "corridor") {
        node.kind = NodeKind::kCorridor;
      } else if (words[4] == "door") {
        node.kind = NodeKind::kDoor;
      } else if (words[4] == "room") {
        node.kind = NodeKind::kRoom;
      } else {
        return fail("'node': kind must be corridor, door or room, not '" + std::string(words[4]) +
                    "'");
      }
      world.nodes.push_back(node);
    } else if (key == "edge") {
      int a, b;
      if (words.size() != 3 || !ParseInteger(words[1], &a) || !ParseInteger(words[2], &b))
        return fail("'edge' needs two node ids");
      const int n = static_cast<int>(world.nodes.size());
      if (a < 0 || a >= n || b < 0 || b >= n || a == b)
        return fail("'edge': node ids must name two different nodes defined above");
      world.edges.push_back(RouteEdge{a, b});
    } else {
      return fail("unknown keyword '" + std::string(key) +
                  "' (expected wall, node, edge or person)");
    }
  }
  if (!have_header) {
    line_no = 0;
    return fail("empty input: no 'atlas-world 1' header");
  }
  return result;
}

void WriteWorld(std::ostream& out, const World& world) {
  std::ostringstream s;
  s << "# atlasd simulator world: walls (m), route graph nodes and edges. See docs/formats.md.\n"
    << "atlas-world 1\n";
  for (const Wall& w : world.walls)
    s << "wall " << Num(w.a.x()) << ' ' << Num(w.a.y()) << ' ' << Num(w.b.x()) << ' '
      << Num(w.b.y()) << (w.glass ? " glass\n" : "\n");
  for (size_t i = 0; i < world.nodes.size(); ++i)
    s << "node " << i << ' ' << Num(world.nodes[i].position.x()) << ' '
      << Num(world.nodes[i].position.y()) << ' ' << ToString(world.nodes[i].kind) << '\n';
  for (const RouteEdge& e : world.edges) s << "edge " << e.from << ' ' << e.to << '\n';
  for (const Person& p : world.people)
    s << "person " << Num(p.a.x()) << ' ' << Num(p.a.y()) << ' ' << Num(p.b.x()) << ' '
      << Num(p.b.y()) << ' ' << Num(p.speed) << '\n';
  out << s.str();
}

}  // namespace atlas::sim
