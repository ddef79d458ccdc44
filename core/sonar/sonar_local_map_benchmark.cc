// Cost of one sonar reading through SonarLocalMap::UpdateSonar (the per-SIP work of the sonar
// path): a full ring fired at once (worse than a P2OS SIP, which carries a few transducers),
// with the map at capacity (gated EKF update only) and with capacity left and a full
// initialisation buffer (update plus one RANSAC / delayed-decision round).

#include <benchmark/benchmark.h>

#include <random>

#include "core/sonar/fake_sonar_ring.h"
#include "core/sonar/sonar_local_map.h"

namespace atlas {
namespace {

std::vector<FakeSonarWall> Rooms() {
  // A corridor with side openings: enough walls for a full map.
  std::vector<FakeSonarWall> w;
  for (int i = 0; i < 6; ++i) {
    const double x0 = 3.0 * i;
    w.push_back({Vec2(x0, 1.2), Vec2(x0 + 2.2, 1.2)});
    w.push_back({Vec2(x0 + 2.2, 1.2), Vec2(x0 + 2.2, 3.0)});
    w.push_back({Vec2(x0 + 0.3, -1.2), Vec2(x0 + 2.8, -1.2)});
  }
  w.push_back({Vec2(18.5, -3), Vec2(18.5, 3)});
  return w;
}

SonarLocalMap MappedCorridor(int capacity) {
  SonarLocalMapOptions o;
  o.line_map.capacity = capacity;
  SonarLocalMap map(o);
  const std::vector<SonarTransducer> ring = FakeSonarRing24();
  std::mt19937_64 rng(3);
  Pose2 truth{};
  for (int i = 0; i < 240; ++i) {
    map.UpdateSonar(FireFakeSonarRing(Rooms(), ring, truth, 0.01, rng), ring, true);
    truth = Compose(truth, Pose2{0.05, 0.0, 0.0});
    map.Predict(Pose2{0.05, 0.0, 0.0});
  }
  return map;
}

void BM_UpdateSonarAtCapacity(benchmark::State& state) {
  const SonarLocalMap base = MappedCorridor(10);
  const std::vector<SonarTransducer> ring = FakeSonarRing24();
  std::mt19937_64 rng(5);
  const SonarReading reading = FireFakeSonarRing(Rooms(), ring, base.RobotPose().mean, 0.01, rng);
  for (auto _ : state) {
    state.PauseTiming();
    SonarLocalMap map = base;
    state.ResumeTiming();
    benchmark::DoNotOptimize(map.UpdateSonar(reading, ring, true));
  }
  state.counters["features"] = base.Complexity();
}
BENCHMARK(BM_UpdateSonarAtCapacity)->Unit(benchmark::kMicrosecond);

void BM_UpdateSonarWithRansac(benchmark::State& state) {
  // Capacity left, buffer full of returns that no feature explains.
  SonarLocalMap base = MappedCorridor(40);
  const std::vector<SonarTransducer> ring = FakeSonarRing24();
  std::mt19937_64 rng(9);
  // Fill the buffer with scattered returns (clutter) without allowing new features.
  std::uniform_real_distribution<double> u(0.3, 5.0);
  for (int k = 0; k < 20; ++k) {
    SonarReading r;
    for (int i = 0; i < 24; ++i) r.returns.push_back(SonarReturn{i, static_cast<float>(u(rng))});
    base.UpdateSonar(r, ring, false);
    base.Predict(Pose2{0.05, 0.0, 0.01});
  }
  const SonarReading reading = FireFakeSonarRing(Rooms(), ring, base.RobotPose().mean, 0.01, rng);
  for (auto _ : state) {
    state.PauseTiming();
    SonarLocalMap map = base;
    state.ResumeTiming();
    benchmark::DoNotOptimize(map.UpdateSonar(reading, ring, true));
  }
  state.counters["features"] = base.Complexity();
  state.counters["buffered"] = static_cast<double>(base.Initializer().Returns().size());
}
BENCHMARK(BM_UpdateSonarWithRansac)->Unit(benchmark::kMicrosecond);

}  // namespace
}  // namespace atlas

BENCHMARK_MAIN();
