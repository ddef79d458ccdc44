#pragma once
// The laser endpoints a frame's map was built from, as a bounded set of occupied cells in the
// frame's coordinates: structure beyond the map's lines, for map-matching's Condition 2
// (paper, Section III-D).
//
// Why: a local map of at most ten lines in a building of long corridors often matches itself
// under shifts of one corridor width or one door spacing (on the corrected aces and
// seattle logs 65-73 % of the map-matching tries were refused as repetitive; docs/design.md,
// "Points: structure beyond the lines").
// The lines alone cannot tell those placements apart, but the scans that made them can: door
// jambs, furniture, wall ends and clutter too short or too scattered to become lines. The cells
// do not form t (t comes from the lines, eq. 9); they only decide between placements the lines
// leave open, and a placement they cannot single out stays refused (map_match.h, "Points").
//
// Contract:
// - Cells are `cell` metres square; a cell is stored once, however many endpoints fall in it.
// - At most `capacity` cells per frame (fixed storage, allocated at the first cell: an
//   open-addressing table of 2 x capacity slots and the cells in insertion order, 4 bytes each,
//   24 kB at the default capacity): endpoints that would need a new cell beyond that are
//   dropped. A frame that never had a mature hypothesis with a laser allocates nothing.
// - Only returns closer than `max_range` are stored (far returns are noisy and unlikely to be
//   seen again from the other frame).
// - ScoreOf() counts the cells of `b` (at most `max_scored` of them, evenly strided) that, moved by
//   the pose of b's frame in this one, land in or next to (3 x 3 neighbourhood) an occupied cell
//   here. O(max_scored x 9), independent of the atlas size.

#include <cstdint>
#include <string>
#include <vector>

#include "core/common/sensor_types.h"
#include "core/geometry/se2.h"

namespace atlas {

struct FramePointsOptions {
  bool enabled = true;
  double cell = 0.1;             // metres
  int capacity = 2048;           // cells per frame
  double max_range = 8.0;        // metres
  int max_scored = 512;          // cells of the other frame scored per placement
  std::string Validate() const;  // empty when valid
  bool operator==(const FramePointsOptions&) const = default;
};

class FramePoints {
 public:
  FramePoints() = default;
  explicit FramePoints(const FramePointsOptions& options) : options_(options) {}

  // Adds the endpoints of `scan` taken with the robot at `robot` (this frame's coordinates).
  void AddScan(const Pose2& robot, const LaserScan& scan);
  // Adds one point in this frame's coordinates; false when it needed a new cell and the set is
  // full.
  bool Add(const Vec2& p);

  int Size() const { return static_cast<int>(cells_.size()); }
  bool Contains(const Vec2& p) const;
  // The number of `b`'s scored cells that land next to one of these (see above), and how many
  // were scored.
  struct Score {
    int hits = 0;
    int scored = 0;
  };
  Score ScoreOf(const FramePoints& b, const Pose2& b_in_this) const;

  // The cells in or next to (3 x 3) one of these, as a bitmap over their bounding box: for
  // scoring many placements against one frame (map-matching's point tests), one look-up per
  // scored cell instead of up to nine. Empty when the box exceeds kMaxNearCells cells.
  struct NearCells {
    int32_t x0 = 0, y0 = 0;  // cell index of the box's first bit
    int32_t width = 0, height = 0;
    std::vector<uint64_t> bits;  // row-major, width * height bits
    bool empty() const { return bits.empty(); }
  };
  static constexpr int64_t kMaxNearCells = int64_t{1} << 24;
  NearCells Near() const;
  // ScoreOf(b, b_in_this).hits, with `near` = Near() of this set unchanged since.
  int HitsNear(const NearCells& near, const FramePoints& b, const Pose2& b_in_this) const;

  // Cell centres, in insertion order.
  std::vector<Vec2> Centres() const;

  const FramePointsOptions& options() const { return options_; }

  // Byte image of the cells (for Atlas::Serialize); Deserialize returns false on a bad image
  // and leaves the set unchanged. An image of more cells than `capacity` keeps the first ones.
  std::string Serialize() const;
  bool Deserialize(const std::string& bytes);

 private:
  static uint32_t Key(int32_t ix, int32_t iy);
  Vec2 Centre(uint32_t key) const;
  bool Has(int32_t ix, int32_t iy) const;
  bool Insert(int32_t ix, int32_t iy);

  FramePointsOptions options_;
  std::vector<uint32_t> slots_;  // key + 1, 0 = empty
  std::vector<uint32_t> cells_;  // keys in insertion order
};

}  // namespace atlas
