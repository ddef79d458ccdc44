// Ray casting cost per laser scan and per sonar reading in a generated 100+ room building.
// The simulator's speed target (10 km in a 100+ room building in seconds) rests on these.

#include <benchmark/benchmark.h>

#include <random>

#include "sim/building_generator.h"
#include "sim/laser_model.h"
#include "sim/ray_caster.h"
#include "sim/sonar_model.h"

namespace atlas::sim {
namespace {

struct Scene {
  World world;
  std::vector<Pose2> poses;  // robot poses on the route graph's corridor and room nodes
  Scene() {
    BuildingOptions o;
    o.min_rooms = 120;
    world = GenerateBuilding(o, 1);
    std::mt19937_64 rng(3);
    std::uniform_real_distribution<double> heading(-3.14159, 3.14159);
    for (const RouteNode& n : world.nodes)
      poses.push_back(Pose2{n.position.x(), n.position.y(), heading(rng)});
  }
};
const Scene& TheScene() {
  static const Scene scene;
  return scene;
}

void BM_LaserScan(benchmark::State& state) {
  const Scene& scene = TheScene();
  const RayCaster caster(scene.world.walls, state.range(1) * 0.25);
  LaserOptions o;
  o.beams = static_cast<int>(state.range(0));
  LaserModel laser(o, 1);
  size_t i = 0;
  for (auto _ : state) {
    LaserScan scan = laser.Scan(caster, scene.poses[i++ % scene.poses.size()], Time{});
    benchmark::DoNotOptimize(scan.ranges.data());
  }
  state.SetItemsProcessed(state.iterations() * o.beams);  // rays
}
// Args: beams, grid cell size in quarter metres.
BENCHMARK(BM_LaserScan)->Args({181, 2})->Args({181, 4})->Args({181, 8})->Args({361, 4});

void BM_LaserScanBruteForce(benchmark::State& state) {
  const Scene& scene = TheScene();
  const RayCaster caster(scene.world.walls, 1.0);
  size_t i = 0;
  for (auto _ : state) {
    const Pose2& p = scene.poses[i++ % scene.poses.size()];
    double sum = 0.0;
    for (int b = 0; b < 181; ++b) {
      const double a = p.theta - 1.5708 + b * 0.017453;
      sum += caster.CastBruteForce(Vec2(p.x, p.y), Vec2(std::cos(a), std::sin(a)), 30.0).range;
    }
    benchmark::DoNotOptimize(sum);
  }
  state.SetItemsProcessed(state.iterations() * 181);
}
BENCHMARK(BM_LaserScanBruteForce);

void BM_SonarReading(benchmark::State& state) {
  const Scene& scene = TheScene();
  const RayCaster caster(scene.world.walls, 1.0);
  SonarModel sonar(SonarOptions{}, 1);
  size_t i = 0;
  for (auto _ : state) {
    SonarReading r = sonar.Read(caster, scene.poses[i++ % scene.poses.size()], Time{});
    benchmark::DoNotOptimize(r.returns.data());
  }
}
BENCHMARK(BM_SonarReading);

}  // namespace
}  // namespace atlas::sim
