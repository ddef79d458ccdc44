// Speed of the local map's per-scan work: line extraction from a 361-beam real scan,
// one EKF update with 10 features, JCBB with 10 features and 10 observations in its worst case.
#include <benchmark/benchmark.h>

#include <Eigen/LU>
#include <string>
#include <variant>

#include "atlas_paths.h"
#include "core/localmap/jcbb.h"
#include "core/localmap/line_ekf_map.h"
#include "core/localmap/line_extraction.h"
#include "core/testing/fake_wall_scanner.h"
#include "logs/carmen/carmen_log.h"
#include "sim/corridor.h"

namespace atlas {
namespace {

// A real scan: the 300th laser scan of mit-csail.clf.gz from ../shared/datasets, read by the
// CARMEN reader (drivers/carmen); a synthetic 361-beam corridor scan if the file is absent (the
// label says which).
LaserScan BenchmarkScan(bool* real) {
  *real = false;
  const std::string path = std::string(ATLAS_SHARED_DIR) + "/datasets/mit-csail/mit-csail.clf.gz";
  const carmen::CarmenReadResult read = carmen::ReadCarmenLog(path, carmen::CarmenLogOptions{});
  int seen = 0;
  for (const carmen::CarmenEvent& e : read.log.events) {
    const auto* scan = std::get_if<LaserScan>(&e.event);
    if (scan != nullptr && scan->ranges.size() == 361 && ++seen == 300) {
      *real = true;
      return *scan;
    }
  }
  FakeWallScanner scanner(sim::CorridorWalls(30.0, 2.4), FakeLaserOptions(), 1);
  return scanner.Scan(Pose2{5.0, 0.2, 0.1});
}

void BM_ExtractLines361(benchmark::State& state) {
  bool real = false;
  const LaserScan scan = BenchmarkScan(&real);
  const LineExtractionOptions options;
  size_t lines = 0;
  for (auto _ : state) {
    auto l = ExtractRobotFrameLines(scan, options);
    lines = l.size();
    benchmark::DoNotOptimize(l);
  }
  state.SetLabel(std::string(real ? "real mit-csail scan, " : "synthetic scan, ") +
                 std::to_string(lines) + " lines");
}
BENCHMARK(BM_ExtractLines361);

// A map of 10 features in a room-like world, and the lines of a scan from a nearby pose.
struct TenFeatureSetup {
  LineEkfMap map;
  std::vector<ObservedLine> observed;
  TenFeatureSetup() : map(Options()) {
    std::vector<sim::Wall> walls;
    for (int k = 0; k < 5; ++k) {  // a zig-zag room: 10 walls in distinct directions
      const double a0 = 2 * M_PI * k / 5, a1 = 2 * M_PI * (k + 0.5) / 5,
                   a2 = 2 * M_PI * (k + 1) / 5;
      const Vec2 p0(6 * std::cos(a0), 6 * std::sin(a0)), p1(4 * std::cos(a1), 4 * std::sin(a1));
      const Vec2 p2(6 * std::cos(a2), 6 * std::sin(a2));
      walls.push_back({p0, p1});
      walls.push_back({p1, p2});
    }
    FakeLaserOptions lo;
    lo.fov = 2 * M_PI * 359.0 / 360.0;
    FakeWallScanner scanner(walls, lo, 2);
    map.Update(scanner.Scan(Pose2{}), true);
    map.Predict(Pose2{0.1, 0.0, 0.01});
    observed = ExtractRobotFrameLines(scanner.Scan(Pose2{0.1, 0.0, 0.01}), LineExtractionOptions());
  }
  static LocalMapOptions Options() {
    LocalMapOptions o;
    o.association.new_feature_min_length = 0.5;
    return o;
  }
};

void BM_EkfUpdate10Features(benchmark::State& state) {
  TenFeatureSetup setup;
  int matched = 0;
  for (auto _ : state) {
    state.PauseTiming();
    LineEkfMap map = setup.map;
    state.ResumeTiming();
    matched = map.UpdateWithLines(setup.observed, false).matched;
    benchmark::DoNotOptimize(map);
  }
  state.SetLabel(std::to_string(setup.map.Complexity()) + " features, " +
                 std::to_string(setup.observed.size()) + " observations, " +
                 std::to_string(matched) + " matched (association + batch update)");
}
BENCHMARK(BM_EkfUpdate10Features);

class RobotOnly final : public JointCovariance {
 public:
  explicit RobotOnly(const std::vector<Mat23>& h) : h_(h) {}
  Mat2 Cross(const CandidatePair& a, const CandidatePair& b) const override {
    return h_[a.tag] * cov_ * h_[b.tag].transpose();
  }
  Mat3 cov_ = Vec3(4.0, 0.01, 1e-4).asDiagonal();

 private:
  const std::vector<Mat23>& h_;
};

// Worst case: ten parallel walls 0.1 m apart and the robot lost along them: all 100 pairings
// individually compatible; the search runs into its node budget.
void BM_Jcbb10x10WorstCase(benchmark::State& state) {
  std::vector<CandidatePair> cands;
  std::vector<Mat23> h;
  const Pose2 robot;
  for (int j = 0; j < 10; ++j) {
    for (int k = 0; k < 10; ++k) {
      LinePrediction p = PredictLine(robot, 3.0 + 0.1 * k, 0.0);
      const Vec2 nu = LineInnovation(Vec2(3.05 + 0.1 * j, 0.0), p);
      const Mat2 s = p.d_pose * Mat3(Vec3(4.0, 0.01, 1e-4).asDiagonal()) * p.d_pose.transpose() +
                     Mat2(Vec2(1e-4, 1e-5).asDiagonal());
      cands.push_back(
          CandidatePair{j, k, nu, s, nu.dot(s.inverse() * nu), static_cast<int>(h.size())});
      h.push_back(p.d_pose);
    }
  }
  const RobotOnly cov(h);
  JcbbOptions o;
  o.node_budget = static_cast<int>(state.range(0));
  int nodes = 0;
  for (auto _ : state) {
    const JcbbResult r = Jcbb(10, cands, cov, o);
    nodes = r.nodes;
    benchmark::DoNotOptimize(r);
  }
  state.SetLabel(std::to_string(nodes) + " nodes");
}
BENCHMARK(BM_Jcbb10x10WorstCase)->Arg(64)->Arg(256);

// The common case: every observation has one compatible feature.
void BM_Jcbb10x10Clear(benchmark::State& state) {
  std::vector<CandidatePair> cands;
  std::vector<Mat23> h;
  for (int j = 0; j < 10; ++j) {
    LinePrediction p = PredictLine(Pose2{}, 3.0 + j, 0.3 * j);
    const Vec2 nu = LineInnovation(Vec2(3.0 + j + 0.001, 0.3 * j), p);
    const Mat2 s = Mat2(Vec2(1e-3, 1e-4).asDiagonal());
    cands.push_back(
        CandidatePair{j, j, nu, s, nu.dot(s.inverse() * nu), static_cast<int>(h.size())});
    h.push_back(p.d_pose);
  }
  const RobotOnly cov(h);
  for (auto _ : state) benchmark::DoNotOptimize(Jcbb(10, cands, cov, JcbbOptions()));
}
BENCHMARK(BM_Jcbb10x10Clear);

}  // namespace
}  // namespace atlas
