#include "core/atlas/frame_points.h"

#include <algorithm>
#include <bit>
#include <cmath>

#include "core/atlas/byte_image.h"

namespace atlas {

namespace {

constexpr int32_t kMaxIndex = 32767;

// The first slot of `key` in a table of mask + 1 slots: the product's high bits folded into
// the low ones, since the low bits of key * odd depend on the key's low bits (one row of
// cells) alone.
size_t FirstSlot(uint32_t key, size_t mask) {
  uint32_t h = key * 2654435761u;
  h ^= h >> 16;
  return h & mask;
}

bool CellIndex(double v, double cell, int32_t* out) {
  const double i = std::floor(v / cell);
  if (!(std::abs(i) <= kMaxIndex)) return false;
  *out = static_cast<int32_t>(i);
  return true;
}

// The cell of `p`; false when it lies beyond the index range.
bool CellOf(const Vec2& p, double cell, int32_t* ix, int32_t* iy) {
  return CellIndex(p.x(), cell, ix) && CellIndex(p.y(), cell, iy);
}

}  // namespace

std::string FramePointsOptions::Validate() const {
  if (!(cell > 0.01 && cell <= 1.0)) return "frame_points.cell must lie in (0.01, 1] metres";
  if (capacity < 16 || capacity > (1 << 20))
    return "frame_points.capacity must lie in [16, 1048576] cells";
  if (!(max_range > 0)) return "frame_points.max_range must be positive";
  if (max_scored < 16) return "frame_points.max_scored must be at least 16";
  return "";
}

uint32_t FramePoints::Key(int32_t ix, int32_t iy) {
  return (static_cast<uint32_t>(ix + 32768) << 16) | static_cast<uint32_t>(iy + 32768);
}

bool FramePoints::Has(int32_t ix, int32_t iy) const {
  if (slots_.empty() || std::abs(ix) > kMaxIndex || std::abs(iy) > kMaxIndex) return false;
  const uint32_t key = Key(ix, iy);
  const size_t mask = slots_.size() - 1;
  for (size_t s = FirstSlot(key, mask);; s = (s + 1) & mask) {
    if (slots_[s] == key) return true;
    if (slots_[s] == 0) return false;
  }
}

bool FramePoints::Insert(int32_t ix, int32_t iy) {
  if (slots_.empty()) {
    slots_.assign(std::bit_ceil(static_cast<size_t>(2 * options_.capacity)), 0);
    cells_.reserve(options_.capacity);
  }
  const uint32_t key = Key(ix, iy);
  const size_t mask = slots_.size() - 1;
  size_t s = FirstSlot(key, mask);
  for (; slots_[s] != 0; s = (s + 1) & mask)
    if (slots_[s] == key) return true;
  if (static_cast<int>(cells_.size()) >= options_.capacity) return false;
  slots_[s] = key;
  cells_.push_back(key);
  return true;
}

bool FramePoints::Add(const Vec2& p) {
  int32_t ix, iy;
  if (!CellOf(p, options_.cell, &ix, &iy)) return false;
  return Insert(ix, iy);
}

void FramePoints::AddScan(const Pose2& robot, const LaserScan& scan) {
  const RigidTransform sensor(Compose(robot, scan.sensor_pose));
  const double max_range = std::min<double>(options_.max_range, scan.max_range);
  for (size_t k = 0; k < scan.ranges.size(); ++k) {
    const double r = scan.ranges[k];
    if (!(r > 0.0 && r < max_range)) continue;
    const double a = scan.angle_min + static_cast<double>(k) * scan.angle_increment;
    if (!Add(sensor.Apply(Vec2(r * std::cos(a), r * std::sin(a)))) && Size() >= options_.capacity)
      return;
  }
}

bool FramePoints::Contains(const Vec2& p) const {
  int32_t ix, iy;
  return CellOf(p, options_.cell, &ix, &iy) && Has(ix, iy);
}

Vec2 FramePoints::Centre(uint32_t key) const {
  const double ix = static_cast<double>(static_cast<int32_t>(key >> 16) - 32768);
  const double iy = static_cast<double>(static_cast<int32_t>(key & 0xffff) - 32768);
  return Vec2((ix + 0.5) * options_.cell, (iy + 0.5) * options_.cell);
}

FramePoints::NearCells FramePoints::Near() const {
  NearCells near;
  if (cells_.empty()) return near;
  int32_t min_x = kMaxIndex, min_y = kMaxIndex, max_x = -kMaxIndex, max_y = -kMaxIndex;
  for (uint32_t key : cells_) {
    const int32_t ix = static_cast<int32_t>(key >> 16) - 32768;
    const int32_t iy = static_cast<int32_t>(key & 0xffff) - 32768;
    min_x = std::min(min_x, ix);
    min_y = std::min(min_y, iy);
    max_x = std::max(max_x, ix);
    max_y = std::max(max_y, iy);
  }
  const int64_t width = int64_t{max_x} - min_x + 3, height = int64_t{max_y} - min_y + 3;
  if (width * height > kMaxNearCells) return near;
  near.x0 = min_x - 1;
  near.y0 = min_y - 1;
  near.width = static_cast<int32_t>(width);
  near.height = static_cast<int32_t>(height);
  near.bits.assign(static_cast<size_t>((width * height + 63) / 64), 0);
  for (uint32_t key : cells_) {
    const int32_t ix = static_cast<int32_t>(key >> 16) - 32768 - near.x0;
    const int32_t iy = static_cast<int32_t>(key & 0xffff) - 32768 - near.y0;
    for (int dy = -1; dy <= 1; ++dy)
      for (int dx = -1; dx <= 1; ++dx) {
        const int64_t bit = int64_t{iy + dy} * near.width + (ix + dx);
        near.bits[static_cast<size_t>(bit >> 6)] |= uint64_t{1} << (bit & 63);
      }
  }
  return near;
}

int FramePoints::HitsNear(const NearCells& near, const FramePoints& b,
                          const Pose2& b_in_this) const {
  if (near.empty()) return ScoreOf(b, b_in_this).hits;
  const int n = b.Size();
  const int stride = std::max(1, (n + options_.max_scored - 1) / options_.max_scored);
  const RigidTransform t(b_in_this);
  int hits = 0;
  for (int k = 0; k < n; k += stride) {
    const Vec2 p = t.Apply(b.Centre(b.cells_[k]));
    int32_t ix, iy;
    if (!CellOf(p, options_.cell, &ix, &iy)) continue;
    const int64_t x = int64_t{ix} - near.x0, y = int64_t{iy} - near.y0;
    if (x < 0 || y < 0 || x >= near.width || y >= near.height) continue;
    const int64_t bit = y * near.width + x;
    hits += static_cast<int>((near.bits[static_cast<size_t>(bit >> 6)] >> (bit & 63)) & 1);
  }
  return hits;
}

std::vector<Vec2> FramePoints::Centres() const {
  std::vector<Vec2> out;
  out.reserve(cells_.size());
  for (uint32_t key : cells_) out.push_back(Centre(key));
  return out;
}

FramePoints::Score FramePoints::ScoreOf(const FramePoints& b, const Pose2& b_in_this) const {
  Score out;
  const int n = b.Size();
  if (n == 0 || slots_.empty()) return out;
  const int stride = std::max(1, (n + options_.max_scored - 1) / options_.max_scored);
  const RigidTransform t(b_in_this);
  for (int k = 0; k < n; k += stride) {
    const Vec2 p = t.Apply(b.Centre(b.cells_[k]));
    ++out.scored;
    int32_t ix, iy;
    if (!CellOf(p, options_.cell, &ix, &iy)) continue;
    bool hit = false;
    for (int dx = -1; dx <= 1 && !hit; ++dx)
      for (int dy = -1; dy <= 1 && !hit; ++dy) hit = Has(ix + dx, iy + dy);
    out.hits += hit ? 1 : 0;
  }
  return out;
}

std::string FramePoints::Serialize() const {
  ByteWriter w;
  w.Put<uint32_t>(static_cast<uint32_t>(cells_.size()));
  w.PutArray(cells_.data(), cells_.size());
  return std::move(w.bytes());
}

bool FramePoints::Deserialize(const std::string& bytes) {
  ByteReader r(bytes);
  uint32_t n = 0;
  if (!r.Get(&n) || n > (1u << 20)) return false;
  std::vector<uint32_t> keys(n);
  for (uint32_t& key : keys)
    if (!r.Get(&key) || key < (1u << 16) || (key & 0xffff) == 0) return false;
  if (!r.AtEnd()) return false;
  slots_.clear();
  cells_.clear();
  for (uint32_t key : keys)
    Insert(static_cast<int32_t>(key >> 16) - 32768, static_cast<int32_t>(key & 0xffff) - 32768);
  return true;
}

}  // namespace atlas
