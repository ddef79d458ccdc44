// One Atlas step with fake local maps, at different atlas sizes: the step cost must not grow
// with the number of frames (constant time, Section I-A).
//
// Warm-up (not timed): the robot explores a meandering path until the atlas holds N frames.
// Timed: the robot shuttles back and forth over the last few metres, so traversal, probation,
// maturation, retirement, map-matching and refinement all run, as they do when a robot works
// in a known area of a large atlas.

#include <benchmark/benchmark.h>

#include "core/atlas/atlas.h"
#include "core/testing/atlas_test_world.h"

namespace atlas {
namespace {

void BM_AtlasStep(benchmark::State& state) {
  const int frames = static_cast<int>(state.range(0));
  TestWorld w;
  w.radius = 1.5;
  w.capacity = 6;
  w.Install();
  AtlasOptions o = TestWorld::Options();
  Atlas atlas(o, w.Factory(), std::make_shared<FakeBootstrapper>());
  const LaserScan scan = TestScan();
  int i = 0;
  while (atlas.Graph().FrameCount() < frames) {
    const double turn = (i / 150) % 2 ? 0.02 : -0.02;
    atlas.Step(Pose2{0.25, 0.0, turn}, scan);
    ++i;
  }
  const int frames_before = atlas.Graph().FrameCount();
  int64_t examined = 0, matched = 0, hypotheses = 0, genesis = 0, seeded = 0, matured = 0;
  int64_t k = 0;
  for (auto _ : state) {
    const double v = (k / 24) % 2 ? -0.25 : 0.25;
    const StepStats& s = atlas.Step(Pose2{v, 0.0, 0.0}, scan);
    examined += s.frames_examined;
    matched += s.candidates_matched;
    hypotheses += s.hypotheses_alive;
    genesis += s.genesis;
    seeded += s.seeded;
    matured += s.matured;
    ++k;
  }
  state.counters["frames_before"] = frames_before;
  state.counters["frames_after"] = atlas.Graph().FrameCount();
  state.counters["examined/step"] = static_cast<double>(examined) / k;
  state.counters["matched/step"] = static_cast<double>(matched) / k;
  state.counters["hyp/step"] = static_cast<double>(hypotheses) / k;
  state.counters["genesis"] = static_cast<double>(genesis);
  state.counters["seeded"] = static_cast<double>(seeded);
  state.counters["matured"] = static_cast<double>(matured);
}
BENCHMARK(BM_AtlasStep)
    ->Arg(10)
    ->Arg(100)
    ->Arg(1000)
    ->Arg(5000)
    ->Iterations(4000)
    ->Repetitions(3)
    ->Unit(benchmark::kMicrosecond);

// The bounded Dijkstra projection alone, on a chain of N frames.
void BM_BoundedProjection(benchmark::State& state) {
  const int n = static_cast<int>(state.range(0));
  AtlasGraph g;
  FrameId prev = g.AddFrame(std::make_unique<FakeLocalMap>());
  for (int f = 1; f < n; ++f) {
    const FrameId id = g.AddFrame(std::make_unique<FakeLocalMap>());
    g.AddEdge(prev, id, UncertainPose{Pose2{1.5, 0.1, 0.05}, Vec3(0.01, 0.01, 0.001).asDiagonal()},
              EdgeKind::kGenesis);
    prev = id;
  }
  DijkstraWorkspace ws;
  Projection p;
  ProjectionLimits limits;
  limits.max_frames = 24;
  for (auto _ : state) {
    ws.Project(g, n / 2, limits, &p);
    benchmark::DoNotOptimize(p.entries.data());
  }
}
BENCHMARK(BM_BoundedProjection)->Arg(10)->Arg(1000)->Arg(100000);

}  // namespace
}  // namespace atlas
