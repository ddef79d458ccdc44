// Cost of one grid update (RangeInserter::Insert) with a 361-beam scan of the 10 x 8 m test
// room (returns up to about 11 m, so about 100 cells crossed per beam), into a grid that
// already covers the room; and the same with no-return beams (an open hall: every beam frees
// space up to no_return_free_range).
#include <benchmark/benchmark.h>

#include "core/testing/grid_scenes.h"
#include "core/grid/range_inserter.h"

namespace atlas {
namespace {

void BM_InsertScan361(benchmark::State& state) {
  const GridOptions o;
  const std::vector<sim::Wall> walls = state.range(0) == 0 ? RoomWalls() : std::vector<sim::Wall>{};
  FakeWallScanner scanner(walls, FullCircleLaser(), 1);
  const Pose2 robot{0.5, -0.3, 0.2};
  RangeScan scan;
  RangeScanFromLaser(scanner.Scan(robot), robot, o.range, &scan);
  ProbabilityGrid grid(o.grid);
  RangeInserter inserter(o.grid);
  InsertionStats stats = inserter.Insert(scan, &grid);
  for (auto _ : state) {
    stats = inserter.Insert(scan, &grid);
    benchmark::DoNotOptimize(grid.values().data());
  }
  state.counters["returns"] = static_cast<double>(scan.returns.size());
  state.counters["cells_updated"] = stats.cells_updated;
}
BENCHMARK(BM_InsertScan361)->Arg(0)->Arg(1);

}  // namespace
}  // namespace atlas
