// Cost of one scan-to-scan match (ScanMatcher::SetReference + Match) on 361-beam scans of the
// simulated corridor world, with the odometry's heading 10 degrees off (the heading search and
// the iterations both run).
#include <benchmark/benchmark.h>

#include "core/scanmatch/scan_matcher.h"
#include "core/testing/fake_wall_scanner.h"
#include "sim/corridor.h"

namespace atlas {
namespace {

void BM_ScanMatch361(benchmark::State& state) {
  FakeLaserOptions laser;
  laser.beams = 361;
  laser.max_range = 30.0;
  laser.sensor_pose = Pose2{0.1, 0.0, 0.0};
  FakeWallScanner scanner(sim::CorridorWalls(), laser, 1);
  const Pose2 a{6.0, 0.3, 0.1}, b{6.25, 0.35, 0.25};
  const LaserScan ref = scanner.Scan(a), cur = scanner.Scan(b);
  const Pose2 truth = Between(a, b);
  ScanMatchOptions o;
  o.enabled = true;
  o.heading_search = state.range(0) / 1000.0;
  ScanMatcher matcher(o);
  UncertainPose prior{Pose2{truth.x, truth.y, truth.theta - 0.1745}, Mat3::Identity() * 0.01};
  int iterations = 0;
  for (auto _ : state) {
    matcher.SetReference(ref);
    const ScanMatchResult r = matcher.Match(cur, prior);
    iterations = r.iterations;
    benchmark::DoNotOptimize(r);
  }
  state.counters["iterations"] = iterations;
}
BENCHMARK(BM_ScanMatch361)->Arg(0)->Arg(350);

}  // namespace
}  // namespace atlas
