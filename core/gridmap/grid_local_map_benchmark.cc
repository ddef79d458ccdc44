// The byte image of a grid frame's map (GridLocalMap::Serialize, Deserialize) at the size a
// frame reaches indoors: a 24 x 18 m room scanned from a tour over its floor, a window of up to
// 512 x 512 cells (counter "bytes": the image's size).

#include <benchmark/benchmark.h>

#include <string>
#include <vector>

#include "core/gridmap/grid_local_map.h"
#include "core/testing/fake_wall_scanner.h"
#include "core/testing/grid_scenes.h"

namespace atlas {
namespace {

GridLocalMap LargeRoomMap() {
  constexpr double kScale = 2.2;
  const std::vector<sim::Wall> walls = RoomWalls(kScale);
  FakeWallScanner scanner(walls, FrontLaser(), 5);
  GridLocalMapOptions o;
  o.max_extent = 100.0;
  GridLocalMap map(o);
  for (const Pose2& p : RoomTour(kScale)) {
    map.ResetRobotPose(UncertainPose{p, Mat3::Zero()});
    map.Update(scanner.Scan(p), true);
  }
  return map;
}

void BM_GridMapSerialize(benchmark::State& state) {
  const GridLocalMap map = LargeRoomMap();
  size_t bytes = 0;
  for (auto _ : state) {
    const std::string image = map.Serialize();
    bytes = image.size();
    benchmark::DoNotOptimize(image.data());
  }
  state.counters["bytes"] = static_cast<double>(bytes);
  state.SetBytesProcessed(static_cast<int64_t>(state.iterations() * bytes));
}
BENCHMARK(BM_GridMapSerialize)->Unit(benchmark::kMicrosecond);

void BM_GridMapDeserialize(benchmark::State& state) {
  const std::string image = LargeRoomMap().Serialize();
  GridLocalMap map;
  for (auto _ : state) {
    const bool ok = map.Deserialize(image);
    benchmark::DoNotOptimize(ok);
  }
  state.counters["bytes"] = static_cast<double>(image.size());
  state.SetBytesProcessed(static_cast<int64_t>(state.iterations() * image.size()));
}
BENCHMARK(BM_GridMapDeserialize)->Unit(benchmark::kMicrosecond);

}  // namespace
}  // namespace atlas
