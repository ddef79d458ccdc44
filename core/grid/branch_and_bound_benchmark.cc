// Cost of map-matching by branch and bound over a +-2 m, +-20 degree window in a 20 x 16 m
// submap (the test room at twice its size, built from twelve scans): precomputing the
// submap's levels (once per submap), and one search (best placement and the runner-up outside
// its peak) for a 361-beam scan (arg 0) or another submap's occupied cells (arg 1).
#include <benchmark/benchmark.h>

#include <limits>

#include "core/grid/branch_and_bound.h"
#include "core/testing/grid_scenes.h"

namespace atlas {
namespace {

void BM_Precompute(benchmark::State& state) {
  const GridOptions o;
  const ProbabilityGrid grid = ScannedGrid(RoomWalls(2.0), RoomTour(2.0), o);
  for (auto _ : state) {
    const PrecomputationGridStack grids(grid, o.search.depth);
    benchmark::DoNotOptimize(&grids);
  }
  state.counters["cells"] = static_cast<double>(grid.values().size());
}
BENCHMARK(BM_Precompute)->Unit(benchmark::kMillisecond);

void BM_BranchAndBound(benchmark::State& state) {
  const GridOptions o;
  const std::vector<sim::Wall> walls = RoomWalls(2.0);
  const ProbabilityGrid grid = ScannedGrid(walls, RoomTour(2.0), o);
  const PrecomputationGridStack grids(grid, o.search.depth);
  const Pose2 truth{2.0, 3.0, 0.7};
  std::vector<Vec2> points;
  if (state.range(0) == 0) {
    points = ScanPoints(walls, truth, o);
  } else {
    std::vector<sim::Wall> moved;
    const RigidTransform to_source(Inverse(truth));
    for (const sim::Wall& w : walls) moved.push_back({to_source.Apply(w.a), to_source.Apply(w.b)});
    std::vector<Pose2> tour;
    for (const Pose2& p : RoomTour(2.0)) tour.push_back(Between(truth, Pose2{-p.x, p.y, -p.theta}));
    points = OccupiedCellCenters(ScannedGrid(moved, tour, o, 5), 0.6);
  }
  const Pose2 center{truth.x + 1.3, truth.y - 0.9, truth.theta + 0.25};
  BranchAndBoundResult r;
  for (auto _ : state) {
    BranchAndBoundSearch search(grids, points, center, o.search);
    search.Run(std::numeric_limits<int64_t>::max());
    r = search.result();
    benchmark::DoNotOptimize(r);
  }
  state.counters["points"] = static_cast<double>(points.size());
  state.counters["nodes"] = static_cast<double>(r.nodes);
  state.counters["margin"] = r.margin;
  state.counters["error_mm"] =
      1000.0 * std::hypot(r.best.pose.x - truth.x, r.best.pose.y - truth.y);
}
BENCHMARK(BM_BranchAndBound)->Arg(0)->Arg(1)->Unit(benchmark::kMillisecond);

}  // namespace
}  // namespace atlas
