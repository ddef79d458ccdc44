#include "core/grid/range_inserter.h"

#include <algorithm>
#include <cassert>
#include <cmath>

namespace atlas {
namespace {

constexpr uint16_t kUpdated = 0x8000;

double Odds(double p) { return p / (1.0 - p); }
double ProbabilityOfOdds(double odds) { return odds / (1.0 + odds); }

std::vector<uint16_t> UpdateTable(const ProbabilityGrid& grid, double probability) {
  std::vector<uint16_t> table(ProbabilityGrid::kMaxValue + 1);
  const double odds = Odds(probability);
  for (int v = 0; v <= ProbabilityGrid::kMaxValue; ++v) {
    const double p =
        v == ProbabilityGrid::kUnknown ? 0.5 : grid.ProbabilityOfValue(static_cast<uint16_t>(v));
    table[v] = grid.ValueOfProbability(ProbabilityOfOdds(Odds(p) * odds)) | kUpdated;
  }
  return table;
}

}  // namespace

void RangeScanFromLaser(const LaserScan& scan, const Pose2& robot, const RangeScanOptions& options,
                        RangeScan* out) {
  const RigidTransform sensor(Compose(robot, scan.sensor_pose));
  out->origin = Vec2(sensor.pose.x, sensor.pose.y);
  out->returns.clear();
  out->misses.clear();
  const size_t n = scan.ranges.size();
  const auto usable = [&](size_t i) {
    return IsReturn(scan.ranges[i]) && scan.ranges[i] < options.max_range;
  };
  const auto endpoint = [&](size_t i) {
    const double a = scan.angle_min + static_cast<double>(i) * scan.angle_increment;
    return Vec2(scan.ranges[i] * std::cos(a), scan.ranges[i] * std::sin(a));
  };
  const double min_sin = std::sin(options.min_incidence);
  // Whether the surface through return i and a neighbouring return j meets the beam at
  // min_incidence or more.
  const auto steep = [&](const Vec2& p, const Vec2& direction, size_t j) {
    const Vec2 t = endpoint(j) - p;
    const double len = t.norm();
    return len > 0.0 && std::abs(direction.x() * t.y() - direction.y() * t.x()) >= min_sin * len;
  };
  for (size_t i = 0; i < n; ++i) {
    const double r = scan.ranges[i];
    const double a = scan.angle_min + static_cast<double>(i) * scan.angle_increment;
    const Vec2 direction(std::cos(a), std::sin(a));
    if (usable(i)) {
      if (r < options.min_range) continue;
      if (options.min_incidence > 0.0) {
        const bool left = i > 0 && usable(i - 1), right = i + 1 < n && usable(i + 1);
        const Vec2 p = r * direction;
        if ((left || right) && !(left && steep(p, direction, i - 1)) &&
            !(right && steep(p, direction, i + 1)))
          continue;
      }
      out->returns.push_back(sensor.Apply(r * direction));
    } else if (options.no_return_free_range > 0.0) {
      out->misses.push_back(sensor.Apply(options.no_return_free_range * direction));
    }
  }
}

RangeInserter::RangeInserter(const ProbabilityGridOptions& options) : options_(options) {
  assert(options_.Validate().empty());
  const ProbabilityGrid grid(options_);
  hit_table_ = UpdateTable(grid, options_.hit_probability);
  miss_table_ = UpdateTable(grid, options_.miss_probability);
}

void RangeInserter::Update(const std::vector<uint16_t>& table, const CellIndex& c,
                           ProbabilityGrid* grid) {
  const GridLimits& l = grid->limits();
  if (!l.Contains(c)) return;
  const int index = l.IndexOf(c);
  uint16_t& value = grid->mutable_values()[index];
  if (value & kUpdated) return;
  if (value == ProbabilityGrid::kUnknown) ++newly_known_;
  value = table[value];
  updated_.push_back(index);
}

void RangeInserter::TraceMisses(const Vec2& from, const Vec2& to, ProbabilityGrid* grid) {
  const GridLimits& l = grid->limits();
  CellIndex c{static_cast<int>(std::floor(from.x())), static_cast<int>(std::floor(from.y()))};
  const CellIndex end{static_cast<int>(std::floor(to.x())), static_cast<int>(std::floor(to.y()))};
  const Vec2 d = to - from;
  const int step_x = d.x() > 0 ? 1 : -1, step_y = d.y() > 0 ? 1 : -1;
  // Ray parameter t in [0, 1] at the next vertical / horizontal cell boundary, and per cell.
  const double inf = std::numeric_limits<double>::infinity();
  const double delta_x = d.x() != 0.0 ? std::abs(1.0 / d.x()) : inf;
  const double delta_y = d.y() != 0.0 ? std::abs(1.0 / d.y()) : inf;
  double next_x = d.x() != 0.0 ? ((step_x > 0 ? c.x + 1 : c.x) - from.x()) / d.x() : inf;
  double next_y = d.y() != 0.0 ? ((step_y > 0 ? c.y + 1 : c.y) - from.y()) / d.y() : inf;
  const int max_steps = std::abs(end.x - c.x) + std::abs(end.y - c.y);
  bool was_inside = false;
  for (int step = 0;; ++step) {
    const bool inside = l.Contains(c);
    if (inside) {
      Update(miss_table_, c, grid);
    } else if (was_inside) {
      return;  // the window is convex: the ray does not come back
    }
    was_inside = was_inside || inside;
    if (c == end || step >= max_steps) return;
    if (next_x < next_y) {
      c.x += step_x;
      next_x += delta_x;
    } else {
      c.y += step_y;
      next_y += delta_y;
    }
  }
}

InsertionStats RangeInserter::Insert(const RangeScan& scan, ProbabilityGrid* grid) {
  assert(grid->options().hit_probability == options_.hit_probability &&
         grid->options().miss_probability == options_.miss_probability &&
         grid->options().min_probability == options_.min_probability &&
         grid->options().max_probability == options_.max_probability);
  InsertionStats stats;
  Vec2 lo = scan.origin, hi = scan.origin;
  for (const std::vector<Vec2>* points : {&scan.returns, &scan.misses}) {
    for (const Vec2& p : *points) {
      lo = lo.cwiseMin(p);
      hi = hi.cwiseMax(p);
    }
  }
  // The sensor's surroundings first: when the cap cuts the scan, what is kept is near it.
  grid->GrowToCover(scan.origin, scan.origin);
  grid->GrowToCover(lo, hi);
  const GridLimits& l = grid->limits();
  updated_.clear();
  newly_known_ = 0;
  for (const Vec2& p : scan.returns) {
    const CellIndex c = l.CellOf(p);
    if (l.Contains(c)) {
      Update(hit_table_, c, grid);
      ++stats.returns_inserted;
    } else {
      ++stats.returns_outside;
    }
  }
  const Vec2 origin = l.CellCoordinates(scan.origin);
  for (const std::vector<Vec2>* points : {&scan.returns, &scan.misses}) {
    for (const Vec2& p : *points) TraceMisses(origin, l.CellCoordinates(p), grid);
  }
  std::vector<uint16_t>& values = grid->mutable_values();
  for (int index : updated_) values[index] &= static_cast<uint16_t>(~kUpdated);
  grid->AddKnownCells(newly_known_);
  stats.cells_updated = static_cast<int>(updated_.size());
  return stats;
}

}  // namespace atlas
