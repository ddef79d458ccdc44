#include "tools/sonar_eval/sonar_atlas_run.h"

#include <Eigen/Cholesky>
#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>

#include "core/localmap/line_model.h"
#include "replay/replay_run.h"
#include "tools/monte_carlo/nees_band.h"
#include "tools/monte_carlo/simulated_base.h"
#include "tools/render/run_data.h"

namespace atlas::sonar_eval {

SonarLocalMapOptions SimulatedMapOptions(RangeSensors sensors, int capacity,
                                         const WheelOdometryNoiseOptions& wheel,
                                         const sim::SonarOptions& sonar) {
  SonarLocalMapOptions o;
  o.sensors = sensors;
  o.ring = sonar.ring;
  o.line_map = LocalMapOptionsOf(MapperSettings{});
  o.line_map.capacity = capacity;
  mc::UseSimulatedWalls(0.01, &o.line_map.extraction);
  o.line_map.odometry = mc::SimulatedBaseOdometry(wheel);
  o.model.range_sigma = sonar.range_sigma;
  o.model.range_sigma_per_m = sonar.range_sigma_per_m;
  return o;
}

MapperSettings SonarEvalMapperSettings(const std::vector<SonarTransducer>& ring,
                                       bool sonar_bootstrap) {
  MapperSettings s;
  s.sensors = RangeSensors::kSonar;
  s.sonar_ring = ring;
  s.sonar_bootstrap = sonar_bootstrap;
  return s;
}

AtlasOptions SonarEvalAtlasOptions(const std::vector<SonarTransducer>& ring, bool sonar_bootstrap,
                                   int probation) {
  AtlasOptions o = AtlasOptionsOf(SonarEvalMapperSettings(ring, sonar_bootstrap));
  if (probation > 0) o.lifecycle.probation_scans = probation;
  return o;
}

AtlasOptions LaserEvalAtlasOptions() {
  MapperSettings lines;
  lines.grid_frames = false;
  return AtlasOptionsOf(lines);
}

int EvalMapCapacity() { return LocalMapOptionsOf(MapperSettings{}).capacity; }

double PoseNees(const UncertainPose& est, const Pose2& truth) {
  const Vec3 e(truth.x - est.mean.x, truth.y - est.mean.y, WrapAngle(truth.theta - est.mean.theta));
  const Mat3 cov = est.cov + Vec3(kNeesFloorM * kNeesFloorM, kNeesFloorM * kNeesFloorM,
                                  kNeesFloorRad * kNeesFloorRad)
                                 .asDiagonal()
                                 .toDenseMatrix();
  return e.dot(cov.ldlt().solve(e));
}

void AddPairError(const Pose2& truth_delta, const Pose2& estimate_delta, std::vector<double>& trans,
                  std::vector<double>& rot_deg) {
  trans.push_back(std::hypot(truth_delta.x - estimate_delta.x, truth_delta.y - estimate_delta.y));
  rot_deg.push_back(std::abs(WrapAngle(truth_delta.theta - estimate_delta.theta)) * 180.0 /
                    std::numbers::pi);
}

Vec2 WallLine(const sim::Wall& wall) {
  const Vec2 d = (wall.b - wall.a).normalized();
  double alpha = std::atan2(d.x(), -d.y());  // normal
  double rho = wall.a.x() * std::cos(alpha) + wall.a.y() * std::sin(alpha);
  CanonicalizeLine(rho, alpha);
  return Vec2(rho, alpha);
}

std::vector<Vec2> WallLinesInFrame(const std::vector<sim::Wall>& walls, const Pose2& origin) {
  const Pose2 to_frame = Inverse(origin);
  std::vector<Vec2> out;
  out.reserve(walls.size());
  for (const sim::Wall& w : walls)
    out.push_back(WallLine(sim::Wall{to_frame.TransformPoint(w.a), to_frame.TransformPoint(w.b)}));
  return out;
}

namespace {
// (rho, alpha) of `line` minus the wall line `w` taken with rho of the same sign (flip) or the
// opposite one.
Vec2 LineDifference(const Vec2& line, const Vec2& w, bool flip) {
  return Vec2(line.x() - (flip ? -w.x() : w.x()),
              WrapAngle(line.y() - w.y() - (flip ? std::numbers::pi : 0.0)));
}
}  // namespace

double NeesAgainstNearestWall(const MapLine& line, const std::vector<Vec2>& wall_lines) {
  double best = std::numeric_limits<double>::infinity();
  const Vec2 l(line.rho, line.alpha);
  const Eigen::LDLT<Mat2> cov = line.cov.ldlt();
  for (const Vec2& w : wall_lines) {
    for (const bool flip : {false, true}) {
      const Vec2 d = LineDifference(l, w, flip);
      best = std::min(best, d.dot(cov.solve(d)));
    }
  }
  return best;
}

bool FarFromEveryWall(const Vec2& line, const std::vector<Vec2>& wall_lines) {
  for (const Vec2& w : wall_lines) {
    for (const bool flip : {false, true}) {
      const Vec2 d = LineDifference(line, w, flip);
      if (std::abs(d.x()) <= 0.25 && std::abs(d.y()) <= 10.0 * std::numbers::pi / 180.0)
        return false;
    }
  }
  return true;
}

void SimRecording::OnLaser(const LaserScan& scan, const Pose2& odometry) {
  Event e;
  e.stamp = scan.stamp;
  e.odometry = odometry;
  e.scan = scan;
  events_.push_back(std::move(e));
}

void SimRecording::OnSonar(const SonarReading& reading, const Pose2& odometry) {
  Event e;
  e.sonar = true;
  e.stamp = reading.stamp;
  e.odometry = odometry;
  e.reading = reading;
  events_.push_back(std::move(e));
}

Pose2 SimRecording::TruthAt(Time t) const { return draw::InterpolateTruth(truth_, t); }

AtlasRunReport RunAtlas(Atlas& atlas, const SimRecording& run, bool sonar,
                        const std::function<void(double)>& progress, const StepObserver& observer) {
  AtlasRunReport r;
  std::vector<std::optional<Pose2>> origin;  // true pose of each frame's origin
  size_t edges_seen = 0;  // graph edges already looked at (edges are only appended)
  bool first = true;
  Pose2 last_odo, odo0;
  const size_t total = run.Events().size();
  for (size_t i = 0; i < total; ++i) {
    const SimRecording::Event& e = run.Events()[i];
    if (progress && i % 1000 == 0) progress(static_cast<double>(i) / total);
    if (e.sonar != sonar) continue;
    const Pose2 u = first ? Pose2{} : Between(last_odo, e.odometry);
    if (first) odo0 = e.odometry;
    first = false;
    last_odo = e.odometry;
    const Pose2 truth = run.TruthAt(e.stamp);
    const int64_t cpu0 = replay::ThreadCpuNs();
    const StepStats& st = sonar ? atlas.Step(u, e.reading) : atlas.Step(u, e.scan);
    const double step_ms = 1e-6 * static_cast<double>(replay::ThreadCpuNs() - cpu0);
    r.max_step_cpu_ms = std::max(r.max_step_cpu_ms, step_ms);
    r.steps_over_10ms += step_ms > 10.0;
    ++r.steps;
    // Frames made this step (the first step's frame 0, or Genesis) have their origin here.
    while (origin.size() < static_cast<size_t>(st.frames)) origin.push_back(truth);
    r.accepted += st.match_accepted;
    r.ambiguous += st.match_ambiguous;
    r.rejected += st.match_rejected;
    for (int k = 0; k < kMapMatchReasonCount; ++k) r.reasons[k] += st.match_reasons[k];
    r.genesis += st.genesis;
    r.seeded += st.seeded;
    r.matured += st.matured;
    r.deleted += st.deleted;
    r.killed_by_w += st.killed_by_w;
    r.frames = st.frames;
    for (; edges_seen < atlas.Graph().Edges().size(); ++edges_seen) {
      const AtlasEdge& edge = atlas.Graph().Edges()[edges_seen];
      if (edge.origin == EdgeKind::kMapMatch && static_cast<size_t>(edge.a) < origin.size() &&
          static_cast<size_t>(edge.b) < origin.size())
        r.as_made.push_back(replay::CheckClosure(edge, *origin[edge.a], *origin[edge.b],
                                                 replay::ClosureCheckOptions{}));
    }
    if (observer) observer(atlas, e.stamp, truth, origin);
    const DominantOutput d = atlas.Dominant();
    if (!d.valid) continue;
    r.truth.push_back(truth);
    r.estimate.push_back(d.pose.mean);
    r.odometry.push_back(Between(odo0, e.odometry));
    r.frame.push_back(d.frame);
    const bool known = d.frame >= 0 && static_cast<size_t>(d.frame) < origin.size();
    r.nees.push_back(known ? PoseNees(d.pose, Between(*origin[d.frame], truth)) : mc::kNoNees);
  }
  r.closures = replay::CheckClosures(atlas.Graph(), origin, replay::ClosureCheckOptions{});
  return r;
}

}  // namespace atlas::sonar_eval
