#pragma once
// Hit/miss updates of a probability grid from one range scan (Hess et al. 2016, Section IV-B,
// eq. 2-3): the cell of each return is a hit, every cell a ray crosses between the sensor
// origin and the return is a miss, and a beam without a return marks free space up to a cap
// only. An update multiplies the cell's odds by odds(hit_probability) or
// odds(miss_probability) and clamps to [min_probability, max_probability]; an unknown cell
// starts at 0.5. Each cell is updated at most once per scan, a hit taking precedence over a
// miss. Rays are traced with a grid traversal that visits every cell the segment crosses
// (Amanatides and Woo 1987). Work per scan is O(returns + cells crossed); no allocation beyond
// the grid's cap and a scratch list of the cells touched.

#include <cstdint>
#include <vector>

#include "core/common/sensor_types.h"
#include "core/grid/grid_options.h"
#include "core/grid/probability_grid.h"

namespace atlas {

// One scan in the submap frame.
struct RangeScan {
  Vec2 origin = Vec2::Zero();  // the sensor
  std::vector<Vec2> returns;   // endpoints of beams with a return
  std::vector<Vec2> misses;    // beams without a return: free space up to these points
};

// The usable beams of `scan` from the robot at `robot` (submap frame): returns in
// [min_range, max_range) become RangeScan::returns; beams without a return or at or beyond
// max_range become misses at no_return_free_range (none when it is 0); shorter returns are
// dropped, and so are returns at grazing incidence (RangeScanOptions::min_incidence).
void RangeScanFromLaser(const LaserScan& scan, const Pose2& robot, const RangeScanOptions& options,
                        RangeScan* out);

struct InsertionStats {
  int returns_inserted = 0;
  int returns_outside = 0;  // returns beyond the grid's cap: not inserted, their rays clipped
  int cells_updated = 0;
};

class RangeInserter {
 public:
  // The probabilities in `options` must be those of the grids it updates.
  explicit RangeInserter(const ProbabilityGridOptions& options);

  // Grows `grid` to cover the scan (as far as its cap allows), then applies the updates.
  InsertionStats Insert(const RangeScan& scan, ProbabilityGrid* grid);

 private:
  // Applies `table` to the cell unless it was already updated during this scan.
  void Update(const std::vector<uint16_t>& table, const CellIndex& c, ProbabilityGrid* grid);
  // Misses along the segment from `from` to `to` (cell units), `to`'s own cell included.
  void TraceMisses(const Vec2& from, const Vec2& to, ProbabilityGrid* grid);

  ProbabilityGridOptions options_;
  // New value | kUpdated for each stored value (index kUnknown: an unknown cell).
  std::vector<uint16_t> hit_table_;
  std::vector<uint16_t> miss_table_;
  std::vector<int> updated_;  // cells updated during the current scan
  int newly_known_ = 0;
};

}  // namespace atlas
