// Cost of one scan-to-grid alignment (ScanAligner::Align: the correlative search over +-0.15 m
// and +-0.09 rad, then Levenberg-Marquardt) of a 361-beam scan against a grid of the 10 x 8 m
// test room built from twelve scans, starting 0.1 m and 3 degrees off. Arg: max_iterations (1:
// about the correlative search's cost alone).
#include <benchmark/benchmark.h>

#include "core/testing/grid_scenes.h"
#include "core/grid/scan_alignment.h"

namespace atlas {
namespace {

void BM_AlignScan361(benchmark::State& state) {
  const GridOptions o;
  const std::vector<sim::Wall> walls = RoomWalls();
  const ProbabilityGrid grid = ScannedGrid(walls, RoomTour(), o);
  const Pose2 truth{1.0, 1.5, 0.7};
  const std::vector<Vec2> points = ScanPoints(walls, truth, o);
  ScanAlignmentOptions ao = o.alignment;
  ao.max_iterations = static_cast<int>(state.range(0));
  ScanAligner aligner(ao);
  AlignmentResult r;
  for (auto _ : state) {
    r = aligner.Align(grid, points, Pose2{truth.x + 0.08, truth.y - 0.06, truth.theta + 0.05});
    benchmark::DoNotOptimize(r);
  }
  state.counters["points"] = r.points;
  state.counters["iterations"] = r.iterations;
  state.counters["error_mm"] =
      1000.0 * std::hypot(r.pose.mean.x - truth.x, r.pose.mean.y - truth.y);
}
BENCHMARK(BM_AlignScan361)->Arg(1)->Arg(20)->Unit(benchmark::kMicrosecond);

}  // namespace
}  // namespace atlas
