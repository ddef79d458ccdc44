// Map-matching two line maps (III-D) at the sizes the step loop meets: maps at capacity, with
// N lines (the paper's 10, and the 24 that MapMatchOptions::max_lines allows). The cost is
// O(N^4) pair hypotheses, each verified in O(N^2): this is the bound of one match per step.
// Office-like maps: mostly two perpendicular wall directions (a corridor with doors and
// rooms), so many line pairs agree in angle and hypotheses are many, as in real buildings.

#include <benchmark/benchmark.h>

#include <cmath>
#include <random>

#include "core/atlas/map_match.h"
#include "core/atlas/segment_line.h"

namespace atlas {
namespace {

MapLine Segment(const Vec2& p, const Vec2& q) { return SegmentLine(p, q, 0.02, 0.01); }

// `n` wall segments of an office floor, seen from frame `pose` (the pose of the map's frame in
// the world); walls are axis-aligned except every fifth, which is at 30 degrees.
std::vector<MapLine> Office(int n, const Pose2& pose, unsigned seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> u(0.0, 12.0), len(1.0, 4.0);
  std::mt19937 walls(7);  // the same walls for every seed: the world
  const Pose2 world_in_map = Inverse(pose);
  std::vector<MapLine> out;
  for (int i = 0; i < n; ++i) {
    const Vec2 p(u(walls), u(walls));
    const double l = len(walls);
    const double a = i % 5 == 4 ? 0.52 : (i % 2 ? 1.5707963 : 0.0);
    const Vec2 q = p + l * Vec2(std::cos(a), std::sin(a));
    std::normal_distribution<double> noise(0.0, 0.01);
    out.push_back(Segment(world_in_map.TransformPoint(p) + Vec2(noise(rng), noise(rng)),
                          world_in_map.TransformPoint(q) + Vec2(noise(rng), noise(rng))));
  }
  return out;
}

void BM_MatchMaps(benchmark::State& state) {
  const int n = static_cast<int>(state.range(0));
  MapMatchOptions o;
  const std::vector<MapLine> a = Office(n, Pose2{}, 1);
  const std::vector<MapLine> b = Office(n, Pose2{0.7, -0.4, 0.3}, 2);
  const SelfMatch sa = SelfMatchMap(a, o), sb = SelfMatchMap(b, o);
  UncertainPose prior;
  prior.mean = Pose2{0.6, -0.3, 0.28};
  prior.cov = Vec3(0.3 * 0.3, 0.3 * 0.3, 0.05 * 0.05).asDiagonal();
  int64_t hypotheses = 0, accepted = 0;
  for (auto _ : state) {
    const MapMatch m = MatchMaps(a, sa, b, sb, &prior, o);
    hypotheses += m.hypotheses;
    accepted += m.result == MapMatchResult::kAccepted;
    benchmark::DoNotOptimize(m);
  }
  state.counters["hypotheses"] =
      benchmark::Counter(static_cast<double>(hypotheses), benchmark::Counter::kAvgIterations);
  state.counters["accepted"] =
      benchmark::Counter(static_cast<double>(accepted), benchmark::Counter::kAvgIterations);
}
BENCHMARK(BM_MatchMaps)->Arg(10)->Arg(16)->Arg(24)->Unit(benchmark::kMicrosecond);

void BM_SelfMatch(benchmark::State& state) {
  const int n = static_cast<int>(state.range(0));
  MapMatchOptions o;
  const std::vector<MapLine> a = Office(n, Pose2{}, 1);
  for (auto _ : state) benchmark::DoNotOptimize(SelfMatchMap(a, o));
}
BENCHMARK(BM_SelfMatch)->Arg(10)->Arg(24)->Unit(benchmark::kMicrosecond);

}  // namespace
}  // namespace atlas
