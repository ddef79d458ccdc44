// Cost of one sonar reading through SonarLocalMap::UpdateSonar (the per-SIP work of the sonar
// path): a full ring fired at once (worse than a P2OS SIP, which carries a few transducers),
// with the map at capacity (gated EKF update only) and with capacity left and a full
// initialisation buffer (update plus one RANSAC / delayed-decision round).

#include <benchmark/benchmark.h>

#include <cmath>
#include <numbers>
#include <random>

#include "core/sonar/sonar_local_map.h"
#include "core/sonar/sonar_map_bootstrapper.h"
#include "core/testing/fake_sonar_ring.h"

namespace atlas {
namespace {

std::vector<sim::Wall> Rooms() {
  // A ten-sided room (circumradius 3 m): every wall can be mapped from a small circle inside.
  std::vector<sim::Wall> w;
  for (int i = 0; i < 10; ++i) {
    const double a0 = 2.0 * std::numbers::pi * i / 10, a1 = 2.0 * std::numbers::pi * (i + 1) / 10;
    w.push_back({Vec2(3.0 * std::cos(a0), 3.0 * std::sin(a0)),
                 Vec2(3.0 * std::cos(a1), 3.0 * std::sin(a1))});
  }
  return w;
}

constexpr Pose2 kCircleStep{0.05, 0.0, 0.05};  // a circle of 1 m radius

SonarLocalMap MappedCorridor(int capacity) {
  SonarLocalMapOptions o;
  o.line_map.capacity = capacity;
  SonarLocalMap map(o);
  const std::vector<SonarTransducer> ring = FakeSonarRing24();
  std::mt19937_64 rng(3);
  Pose2 truth{0.0, -1.0, 0.0};
  map.ResetRobotPose(UncertainPose{truth, Mat3::Zero()});
  const Pose2 u{0.05, 0.0, 0.05};  // a circle of 1 m radius
  for (int i = 0; i < 500; ++i) {
    map.UpdateSonar(FireFakeSonarRing(Rooms(), ring, truth, 0.01, rng), ring, true);
    truth = Compose(truth, u);
    map.Predict(u);
  }
  return map;
}

// The room mapped at capacity 10 through LocalMap::UpdateWithSonar with `ring`, driving 500
// steps round a 1 m circle; `truth` (the robot's pose in the map) and `rng` go on from there.
SonarLocalMap MappedRoom(const std::vector<SonarTransducer>& ring, Pose2& truth,
                         std::mt19937_64& rng) {
  SonarLocalMapOptions o;
  o.line_map.capacity = 10;
  o.ring = ring;
  SonarLocalMap map(o);
  truth = Pose2{0.0, -1.0, 0.0};
  map.ResetRobotPose(UncertainPose{truth, Mat3::Zero()});
  for (int i = 0; i < 500; ++i) {
    map.UpdateWithSonar(FireFakeSonarRing(Rooms(), o.ring, truth, 0.01, rng), true);
    truth = Compose(truth, kCircleStep);
    map.Predict(kCircleStep);
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

// The Atlas's per-SIP call (LocalMap::UpdateWithSonar, ring from the options) for a reading of
// the whole ring (16 or 24 transducers), with the map built with that ring and at capacity
// (10 features): the gated EKF update and one delayed-decision round on the buffer.
void BM_UpdateWithSonarFullRing(benchmark::State& state) {
  std::mt19937_64 rng(3);
  Pose2 truth;
  const SonarLocalMap base =
      MappedRoom(FakeSonarRing(static_cast<int>(state.range(0))), truth, rng);
  const SonarReading reading = FireFakeSonarRing(Rooms(), base.Options().ring, truth, 0.01, rng);
  int matched = 0;
  for (auto _ : state) {
    state.PauseTiming();
    SonarLocalMap map = base;
    state.ResumeTiming();
    const ScanUpdate up = map.UpdateWithSonar(reading, true);
    matched = up.matched;
    benchmark::DoNotOptimize(up);
  }
  state.counters["features"] = base.Complexity();
  state.counters["returns"] = static_cast<double>(reading.returns.size());
  state.counters["matched"] = matched;
}
BENCHMARK(BM_UpdateWithSonarFullRing)->Arg(16)->Arg(24)->Unit(benchmark::kMicrosecond);

// A mapped corridor (capacity left) whose initialiser buffer holds clutter that no feature
// explains: `steps` readings of `per_step` random returns, moving `u` after each; then times
// UpdateSonar with a full-ring reading (the EKF update and one RANSAC / decision round).
void TimeUpdateWithClutter(benchmark::State& state, uint64_t seed, int steps, int per_step,
                           const Pose2& u) {
  SonarLocalMap base = MappedCorridor(40);
  const std::vector<SonarTransducer> ring = FakeSonarRing24();
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<double> range(0.3, 5.0);
  std::uniform_int_distribution<int> which(0, 23);
  for (int k = 0; k < steps; ++k) {
    SonarReading r;
    for (int i = 0; i < per_step; ++i) {
      const int t = per_step == 24 ? i : which(rng);
      r.returns.push_back(SonarReturn{t, static_cast<float>(range(rng))});
    }
    base.UpdateSonar(r, ring, false);
    base.Predict(u);
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
  state.counters["vantages"] = base.Vantages().Size();
}

// Capacity left, buffer full of returns of the whole ring that no feature explains.
void BM_UpdateSonarWithRansac(benchmark::State& state) {
  TimeUpdateWithClutter(state, 9, 20, 24, Pose2{0.05, 0.0, 0.01});
}
BENCHMARK(BM_UpdateSonarWithRansac)->Unit(benchmark::kMicrosecond);

// The bound of the delayed states (delayed_vantages.h): max_vantage (128) vantage points with
// buffered returns, i.e. 384 extra rows correlated with the EKF, updated with a full ring's
// pairings, plus one RANSAC / delayed-decision round on the full buffer.
void BM_UpdateSonarAllVantagePoints(benchmark::State& state) {
  TimeUpdateWithClutter(state, 11, 2 * SonarInitOptions{}.max_vantage, 2, Pose2{0.01, 0.0, 0.005});
}
BENCHMARK(BM_UpdateSonarAllVantagePoints)->Unit(benchmark::kMicrosecond);

// Cost of the sonar w (SonarMapBootstrapper::Solve, eq. 12) on a map at capacity (10 lines of a
// ten-sided room) for Z of N readings, each of the whole 24-transducer ring (the worst case: a
// P2OS SIP or the simulator carries about 4 returns); the atlas calls it once per juvenile and
// step from bootstrap_scans until it solves or probation (kSonarBootstrapProbation) ends.
// Measured (RelWithDebInfo, shared 2-core VM, load 4-6): N = 4, 190 us CPU (undetermined: the
// heading's sigma 0.11 rad from one place); N = 30 (720 returns), 2.2 ms CPU, solved.
void BM_SonarWSolve(benchmark::State& state) {
  const int readings = static_cast<int>(state.range(0));
  std::mt19937_64 rng(3);
  Pose2 truth;
  const SonarLocalMap frame = MappedRoom(FakeSonarRing24(), truth, rng);
  const Pose2 u = kCircleStep;
  std::unique_ptr<LocalMap> trial = frame.Clone();
  const UncertainPose seed{Compose(truth, Pose2{0.1, -0.1, 0.05}),
                           Vec3(0.04, 0.04, 0.01).asDiagonal()};
  trial->ResetRobotPose(seed);
  std::vector<JuvenileScan> z;
  for (int i = 0; i < readings; ++i) {
    truth = Compose(truth, u);
    JuvenileScan s;
    s.odometry_delta = u;
    s.sonar = FireFakeSonarRing(Rooms(), frame.Options().ring, truth, 0.01, rng);
    trial->Predict(u);
    trial->UpdateWithSonar(s.sonar, false);
    z.push_back(s);
  }
  const SonarMapBootstrapper w;
  int solved = 0;
  for (auto _ : state) {
    const PoseBootstrap r = w.Solve(*trial, frame, z, seed);
    solved = r.outcome == BootstrapOutcome::kSolved ? 1 : 0;
    benchmark::DoNotOptimize(r.pose);
  }
  state.counters["features"] = frame.Complexity();
  state.counters["solved"] = solved;
}
BENCHMARK(BM_SonarWSolve)->Arg(4)->Arg(30)->Unit(benchmark::kMicrosecond);

}  // namespace
}  // namespace atlas

BENCHMARK_MAIN();
