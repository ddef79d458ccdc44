#pragma once
// The atlas part of atlas-sonar-eval: a simulated run recorded once, then stepped
// through an Atlas (paper, Sections II-III) of sonar-only SonarLocalMaps or of laser maps, with
// the ground truth kept beside it.
//
// What a run reports:
// - map-matching outcomes (III-D) summed over the steps, by MapMatchReason: accepted, refused as
//   ambiguous (Condition 2, II-A: repetitive structure inside the prior), rejected;
// - every edge made by map-matching checked against the ground truth (tools/replay
//   closure_check.h: the reference pose of frame b in frame a from the true poses at the
//   frames' origins; chi-square 3 dof > 14.16 is a false closure), as it ended up and as
//   map-matching made it;
// - the dominant hypothesis's robot pose (its output, III-E) in its own frame against the true
//   pose in that frame, per step: NEES (3 dof) and relative-pose errors.
// A frame's origin is the true pose at the step that created it (Genesis, III-C: the robot is
// at exactly zero in the new frame).

#include <array>
#include <functional>
#include <optional>
#include <vector>

#include "core/atlas/atlas.h"
#include "core/mapper/mapper_factory.h"
#include "core/sonar/sonar_options.h"
#include "replay/closure_check.h"
#include "sim/simulation.h"
#include "sim/wheel_odometry_model.h"

namespace atlas::sonar_eval {

// The mapper settings of the evaluation's sonar atlas: atlasd's for the sonar ring alone
// (MapperSettings' defaults, equal to config/atlasd.toml, with sensors kSonar), on the ring
// `ring` (the simulated one), with w (eq. 12) from the sonar when `sonar_bootstrap`.
MapperSettings SonarEvalMapperSettings(const std::vector<SonarTransducer>& ring,
                                       bool sonar_bootstrap);

// The options of the sonar atlas of atlas-sonar-eval atlas: the atlas atlasd builds from those
// settings (AtlasOptionsOf); `probation` > 0 replaces lifecycle.probation_scans.
AtlasOptions SonarEvalAtlasOptions(const std::vector<SonarTransducer>& ring, bool sonar_bootstrap,
                                   int probation = 0);
// The options of its laser atlas: atlasd's for line maps of the laser alone (the paper's
// Section IV compares line maps), AtlasOptionsOf(MapperSettings) with grid_frames off.
AtlasOptions LaserEvalAtlasOptions();
// The map capacity of both atlases' maps unless --capacity gives one: atlasd's.
int EvalMapCapacity();

// The EKF options of the evaluation's maps: atlasd's (LocalMapOptionsOf(MapperSettings{})) with
// capacity `capacity` and the noise models of the simulated hardware, as a config's noise keys
// describe a robot: odometry noise and calibration errors as simulated, the laser's and the
// sonar's range noise as the simulator draws them; the sonar's misfit noise stays atlasd's.
SonarLocalMapOptions SimulatedMapOptions(RangeSensors sensors, int capacity,
                                         const WheelOdometryNoiseOptions& wheel,
                                         const sim::SonarOptions& sonar);

// NEES (3 dof) of `estimate` against `truth` (heading difference wrapped). The covariance gets
// a floor of (1 mm)^2, (1 mm)^2, (1 mrad)^2, the size of the ground truth's own error (linear
// interpolation between 50 Hz samples): right after Genesis the pose covariance is zero or of
// rank 2 (wheel noise moves x and theta only), and a truth error of a micrometre across it
// would read as a NEES of 10^5, dominating any mean.
inline constexpr double kNeesFloorM = 1e-3, kNeesFloorRad = 1e-3;
double PoseNees(const UncertainPose& estimate, const Pose2& truth);

// The error of one pair of poses some time apart: the distance (m) and the heading difference
// (degrees) between the true relative pose and the estimated one, appended to `trans` and
// `rot_deg`.
void AddPairError(const Pose2& truth_delta, const Pose2& estimate_delta, std::vector<double>& trans,
                  std::vector<double>& rot_deg);

// Line features against the simulator's walls. Lines are canonical (rho, alpha)
// (CanonicalizeLine) in a map frame whose true origin is `origin`.
// The infinite line through a wall, in the coordinates its endpoints are given in.
Vec2 WallLine(const sim::Wall& wall);
// Every wall's line in the frame whose true origin is `origin`.
std::vector<Vec2> WallLinesInFrame(const std::vector<sim::Wall>& walls, const Pose2& origin);
// The smallest NEES (2 dof, the line's own covariance) of `line` against any of `wall_lines`
// (either orientation of each): above the 99.9 % point (13.8) the line fits no wall.
double NeesAgainstNearestWall(const MapLine& line, const std::vector<Vec2>& wall_lines);
// True when the line (rho, alpha) is farther than 0.25 m in rho or 10 degrees in alpha from
// every wall line: a phantom (the count atlas-sonar-eval mc prints at initialisation).
bool FarFromEveryWall(const Vec2& line, const std::vector<Vec2>& wall_lines);

// A whole simulated run in memory: ground truth, and every laser scan and sonar reading with
// the odometry pose at its stamp, in stamp order.
class SimRecording final : public sim::SimulationSink {
 public:
  struct Event {
    bool sonar = false;
    Time stamp{};
    Pose2 odometry;
    LaserScan scan;
    SonarReading reading;
  };
  void OnTruth(const TruthSample& t) override { truth_.push_back(t); }
  void OnOdometry(const OdometrySample&, double, double) override {}
  void OnLaser(const LaserScan& scan, const Pose2& odometry) override;
  void OnSonar(const SonarReading& reading, const Pose2& odometry) override;

  const std::vector<Event>& Events() const { return events_; }
  bool Empty() const { return truth_.empty(); }
  // The true pose at `t`, interpolated between the samples around it.
  Pose2 TruthAt(Time t) const;

 private:
  std::vector<TruthSample> truth_;
  std::vector<Event> events_;
};

struct AtlasRunReport {
  // Per step with a dominant hypothesis.
  std::vector<Pose2> truth, estimate, odometry;  // estimate in its frame; odometry from start
  std::vector<FrameId> frame;
  std::vector<double>
      nees;  // of the dominant pose in its frame; mc::kNoNees when the origin is unknown
  int steps = 0, frames = 0, genesis = 0;
  int accepted = 0, ambiguous = 0, rejected = 0;
  // Traversal juveniles (III-E): seeded, matured, deleted (of which killed by w, eq. 12).
  int seeded = 0, matured = 0, deleted = 0, killed_by_w = 0;
  // The stepping thread's CPU time per Atlas::Step (CLOCK_THREAD_CPUTIME_ID): the largest, and
  // the steps over 10 ms (atlasd's default step budget).
  double max_step_cpu_ms = 0.0;
  int steps_over_10ms = 0;
  std::array<int, kMapMatchReasonCount> reasons{};
  replay::ClosureReport closures;  // the map-match edges of the final graph vs ground truth
  // The same edges as map-matching made them (before any edge refinement, III-F), in the order
  // made: a false closure here is map-matching's; one only in `closures` came from refinement.
  std::vector<replay::ClosureVerdict> as_made;
};

// Called after every step with the atlas, the event's stamp, the true pose (world) and the true
// poses of the frames' origins so far (index = frame id).
using StepObserver =
    std::function<void(const Atlas&, Time, const Pose2&, const std::vector<std::optional<Pose2>>&)>;

// Steps `atlas` through the sonar readings (`sonar`) or the laser scans of `run`. `progress`
// (may be empty) is called every 1000 events with the fraction done; `observer` (may be empty)
// after every step.
AtlasRunReport RunAtlas(Atlas& atlas, const SimRecording& run, bool sonar,
                        const std::function<void(double)>& progress = {},
                        const StepObserver& observer = {});

}  // namespace atlas::sonar_eval
