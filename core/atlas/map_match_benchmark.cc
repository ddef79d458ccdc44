// Map-matching two line maps (III-D) at the sizes the step loop meets: maps at capacity, with
// N lines (the paper's 10, and the 24 that MapMatchOptions::max_lines allows). The cost is
// O(N^4) pair hypotheses, each verified in O(N^2): this is the bound of one match per step.
// Office-like maps: mostly two perpendicular wall directions (a corridor with doors and
// rooms), so many line pairs agree in angle and hypotheses are many, as in real buildings.

#include <benchmark/benchmark.h>

#include <algorithm>
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

// The points' second look (map_match.h, "Points") at its largest: a corridor with a bay every
// 2 m (ten lines that repeat, so the lines alone are ambiguous), frames full of points (2048
// cells each: the walls of the part of the corridor B saw, and clutter in the rooms beside it)
// and a loose prior, so that many placements and repetitions inside the gate are scored; with
// atlasd's laser settings (LaserMapMatchOptions: alternative lines scored by the points too).
void BM_MatchMapsWithPoints(benchmark::State& state) {
  const MapMatchOptions o = LaserMapMatchOptions();
  const Pose2 b_in_a{6.0, 0.4, 0.2};
  std::vector<std::pair<Vec2, Vec2>> walls{{{0, 0}, {14, 0}}, {{0, -2.4}, {14, -2.4}}};
  for (double x = 0; x <= 14; x += 2) walls.push_back({{x, 0}, {x, 1.5}});
  const auto lines_in = [&walls](const Pose2& frame, double x0, double x1) {
    const Pose2 world_in_frame = Inverse(frame);
    std::vector<MapLine> out;
    for (const auto& [p, q] : walls) {
      if (std::max(p.x(), q.x()) < x0 || std::min(p.x(), q.x()) > x1) continue;
      const Vec2 a(std::clamp(p.x(), x0, x1), p.y()), b(std::clamp(q.x(), x0, x1), q.y());
      out.push_back(Segment(world_in_frame.TransformPoint(a), world_in_frame.TransformPoint(b)));
    }
    return out;
  };
  const std::vector<MapLine> a = lines_in(Pose2{}, 0, 14), b = lines_in(b_in_a, 4, 12);
  FramePointsOptions po;
  po.enabled = true;
  FramePoints pa(po), pb(po);
  std::mt19937 rng(3);
  std::uniform_real_distribution<double> x(4.0, 12.0), y(-25.0, 25.0);
  for (int k = 0; k < 20000 && (pa.Size() < po.capacity || pb.Size() < po.capacity); ++k) {
    const Vec2 p = k % 2 ? Vec2(x(rng), k % 4 == 1 ? 0.0 : -2.4) : Vec2(x(rng), y(rng));
    pa.Add(p);
    pb.Add(Inverse(b_in_a).TransformPoint(p));
  }
  const SelfMatch sa = SelfMatchMap(a, o), sb = SelfMatchMap(b, o);
  UncertainPose prior;
  prior.mean = Pose2{6.5, 0.2, 0.22};
  prior.cov = Vec3(2.0 * 2.0, 0.5 * 0.5, 0.05 * 0.05).asDiagonal();
  int64_t by_points = 0;
  state.SetLabel(MapMatchReasonName(MatchMaps(a, sa, b, sb, &prior, o, &pa, &pb).reason));
  for (auto _ : state) {
    const MapMatch m = MatchMaps(a, sa, b, sb, &prior, o, &pa, &pb);
    by_points += m.by_points;
    benchmark::DoNotOptimize(m);
  }
  state.counters["by_points"] =
      benchmark::Counter(static_cast<double>(by_points), benchmark::Counter::kAvgIterations);
  state.counters["cells_a"] = pa.Size();
  state.counters["cells_b"] = pb.Size();
}
BENCHMARK(BM_MatchMapsWithPoints)->Unit(benchmark::kMicrosecond);

void BM_SelfMatch(benchmark::State& state) {
  const int n = static_cast<int>(state.range(0));
  MapMatchOptions o;
  const std::vector<MapLine> a = Office(n, Pose2{}, 1);
  for (auto _ : state) benchmark::DoNotOptimize(SelfMatchMap(a, o));
}
BENCHMARK(BM_SelfMatch)->Arg(10)->Arg(24)->Unit(benchmark::kMicrosecond);

}  // namespace
}  // namespace atlas
