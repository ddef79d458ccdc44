#include "sim/ray_caster.h"

#include <algorithm>
#include <cassert>
#include <cmath>
#include <limits>

namespace atlas::sim {
namespace {

constexpr double kInf = std::numeric_limits<double>::infinity();

}  // namespace

RayCaster::RayCaster(const std::vector<Wall>& walls, double cell_size)
    : walls_(walls), cell_(cell_size) {
  assert(cell_size > 0.0);
  for (const Wall& w : walls_)
    packed_.push_back({w.a.x(), w.a.y(), w.b.x() - w.a.x(), w.b.y() - w.a.y()});
  Bounds b;
  for (const Wall& w : walls_) {
    b.Extend(w.a);
    b.Extend(w.b);
  }
  if (b.empty) b.Extend(Vec2::Zero());
  origin_ = b.min - Vec2(cell_, cell_);
  nx_ = static_cast<int>(std::ceil((b.max.x() - origin_.x()) / cell_)) + 1;
  ny_ = static_cast<int>(std::ceil((b.max.y() - origin_.y()) / cell_)) + 1;
  std::vector<int> count(static_cast<size_t>(nx_) * ny_ + 1, 0);
  auto cells_of = [&](const Wall& w, auto&& visit) {
    const int x0 = static_cast<int>((std::min(w.a.x(), w.b.x()) - origin_.x()) / cell_);
    const int x1 = static_cast<int>((std::max(w.a.x(), w.b.x()) - origin_.x()) / cell_);
    const int y0 = static_cast<int>((std::min(w.a.y(), w.b.y()) - origin_.y()) / cell_);
    const int y1 = static_cast<int>((std::max(w.a.y(), w.b.y()) - origin_.y()) / cell_);
    for (int y = y0; y <= y1; ++y)
      for (int x = x0; x <= x1; ++x) visit(y * nx_ + x);
  };
  for (const Wall& w : walls_)
    if (!w.glass) cells_of(w, [&](int c) { ++count[c + 1]; });
  for (size_t i = 1; i < count.size(); ++i) count[i] += count[i - 1];
  cell_start_ = count;
  cell_walls_.resize(count.back());
  for (int i = 0; i < static_cast<int>(walls_.size()); ++i)
    if (!walls_[i].glass) cells_of(walls_[i], [&](int c) { cell_walls_[count[c]++] = i; });
}

inline double RayCaster::Intersect(int i, double ox, double oy, double ux, double uy) const {
  const PackedWall& w = packed_[i];
  double denom = ux * w.dy - uy * w.dx;
  const double aox = w.ax - ox, aoy = w.ay - oy;
  double tn = aox * w.dy - aoy * w.dx;
  double sn = aox * uy - aoy * ux;
  if (denom < 0.0) denom = -denom, tn = -tn, sn = -sn;
  // Hit iff denom > 0 (not parallel: grazing walls are not seen), t > 0, 0 <= s <= 1.
  if (denom < 1e-12 || tn <= 1e-9 * denom || sn < 0.0 || sn > denom) return kInf;
  return tn / denom;
}

RayHit RayCaster::CastBruteForce(const Vec2& origin, const Vec2& direction,
                                 double max_range) const {
  const Vec2 u = direction.normalized();
  RayHit best{kInf, -1};
  for (int i = 0; i < num_walls(); ++i) {
    if (walls_[i].glass) continue;
    const double t = Intersect(i, origin.x(), origin.y(), u.x(), u.y());
    if (t < best.range) best = {t, i};
  }
  if (best.range > max_range) return RayHit{max_range, -1};
  return best;
}

RayHit RayCaster::Cast(const Vec2& origin, const Vec2& direction, double max_range) const {
  const Vec2 u = direction.normalized();
  // Clip the ray to the grid box; walls lie strictly inside it.
  double t0 = 0.0, t1 = max_range;
  const Vec2 lo = origin_, hi = origin_ + Vec2(nx_ * cell_, ny_ * cell_);
  for (int k = 0; k < 2; ++k) {
    if (std::abs(u[k]) < 1e-15) {
      if (origin[k] < lo[k] || origin[k] >= hi[k]) return RayHit{max_range, -1};
    } else {
      double ta = (lo[k] - origin[k]) / u[k], tb = (hi[k] - origin[k]) / u[k];
      if (ta > tb) std::swap(ta, tb);
      t0 = std::max(t0, ta);
      t1 = std::min(t1, tb);
    }
  }
  if (t0 > t1) return RayHit{max_range, -1};

  const Vec2 start = origin + t0 * u - origin_;
  int cx = std::clamp(static_cast<int>(start.x() / cell_), 0, nx_ - 1);
  int cy = std::clamp(static_cast<int>(start.y() / cell_), 0, ny_ - 1);
  const int step_x = u.x() > 0 ? 1 : -1, step_y = u.y() > 0 ? 1 : -1;
  const Vec2 rel = origin - origin_;
  auto next_boundary = [&](int c, int step, double o, double d) {
    if (std::abs(d) < 1e-15) return kInf;
    const double edge = (c + (step > 0 ? 1 : 0)) * cell_;
    return (edge - o) / d;
  };
  double t_max_x = next_boundary(cx, step_x, rel.x(), u.x());
  double t_max_y = next_boundary(cy, step_y, rel.y(), u.y());
  const double t_delta_x = std::abs(u.x()) < 1e-15 ? kInf : cell_ / std::abs(u.x());
  const double t_delta_y = std::abs(u.y()) < 1e-15 ? kInf : cell_ / std::abs(u.y());

  RayHit best{kInf, -1};
  while (true) {
    const int c = cy * nx_ + cx;
    for (int k = cell_start_[c]; k < cell_start_[c + 1]; ++k) {
      const int i = cell_walls_[k];
      const double t = Intersect(i, origin.x(), origin.y(), u.x(), u.y());
      if (t < best.range) best = {t, i};
    }
    const double t_exit = std::min(t_max_x, t_max_y);
    if (best.range <= t_exit || t_exit > t1) break;
    if (t_max_x < t_max_y) {
      cx += step_x;
      t_max_x += t_delta_x;
      if (cx < 0 || cx >= nx_) break;
    } else {
      cy += step_y;
      t_max_y += t_delta_y;
      if (cy < 0 || cy >= ny_) break;
    }
  }
  if (best.range > max_range) return RayHit{max_range, -1};
  return best;
}

}  // namespace atlas::sim
