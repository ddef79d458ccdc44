#pragma once
// Competing map-frame hypotheses (paper, Sections III-B and III-E, Fig. 4).
//
// A hypothesis is the claim "the robot is in map-frame F at pose x". Each frame carries at most
// one hypothesis and the total count is bounded (the Atlas enforces both). States:
//   juvenile  seeded by traversal (eq. 10-11) in a retired frame; processes scans against its
//             map but may not extend it (Update(..., allow_new_features = false)). It works on a
//             private clone of the frame's map, so a juvenile that is deleted leaves the frame's
//             map untouched; on maturation the clone replaces the frame's map.
//   mature    extends its map; the mature hypothesis with the best q is the dominant one, the
//             output of the framework.
//   retired   a mature hypothesis that failed. Its frame keeps the map; the frame may later be
//             reactivated by a juvenile.
// Transitions (pure functions below, applied by the Atlas once per step):
//   juvenile -> deleted    w (eq. 12) failed after the bootstrap scans (or was still
//                          undetermined at the end of probation), or at the end of probation
//                          its q does not beat every mature hypothesis;
//   juvenile -> mature     at the end of probation its q beats every mature hypothesis (or no
//                          mature hypothesis exists);
//   mature   -> retired    q stayed below q_fail for fail_steps consecutive steps while another
//                          mature hypothesis exists (if it is the only one, Genesis first);
//                          or, not being the dominant one, its q stayed more than retire_margin
//                          below the dominant's q for lag_steps consecutive steps.
// Why the second rule: eq. 5's first term stays near 1 while the robot's pose in a frame is
// well known, so a hypothesis whose map explains none of the scans keeps q near alpha (0.5 by
// default) and never falls below an absolute q_fail that healthy sonar maps (which explain a
// small share of their echoes) must stay above. The paper retires mature hypotheses "that fail
// to perform well"; measured against the dominant one, a frame the robot has left fails: its
// hypothesis stops running (drifting along corridors, pairing returns with the wrong wall) and
// the frame is reached again by traversal (a juvenile, w, probation) when the robot returns.
//
// Quality metric q, eq. 5:
//   q = alpha (1 - det(Sigma_x) / det(Sigma_*)) + (1 - alpha) eta_a / ||Z^k||,
// with det(Sigma_*) = sigma_x^2 sigma_y^2 sigma_theta^2. The first term is clamped at 0 (a pose
// less certain than the acceptable maximum contributes nothing). "Recent observations" Z^k are
// the last `window` scans: eta_a and ||Z|| are sums over the window. A window without any
// observation has explanation `empty_explanation` (default 0: a featureless stretch counts as
// unexplained, as the paper's q "tends to zero" when measurements stop matching).

#include <Eigen/LU>
#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include "core/atlas/atlas_graph.h"
#include "core/common/sensor_types.h"
#include "core/localmap/local_map.h"
#include "core/localmap/scan_observation.h"

namespace atlas {

struct HypothesisQualityOptions {
  double alpha = 0.5;
  double sigma_x = 1.0;       // metres: maximum acceptable robot uncertainty, eq. 5
  double sigma_y = 1.0;       // metres
  double sigma_theta = 0.35;  // radians
  int window = 5;             // scans in Z^k
  double empty_explanation = 0.0;
  std::string Validate() const;  // empty when valid
  bool operator==(const HypothesisQualityOptions&) const = default;
};

// eq. 5. `explanation` is eta_a / ||Z^k|| in [0, 1].
double HypothesisQuality(const Mat3& robot_cov, double explanation,
                         const HypothesisQualityOptions& options);

// The last `window` (observations, matched) pairs. Fixed capacity.
class QualityWindow {
 public:
  explicit QualityWindow(int window = 5) : capacity_(window) {}
  void Add(const ScanUpdate& u);
  void Clear();
  int Observations() const { return observations_; }
  int Matched() const { return matched_; }
  int Size() const { return size_; }
  int Capacity() const { return capacity_; }
  // eta_a / ||Z^k||, or `empty` when the window holds no observation.
  double Explanation(double empty) const;
  struct Entry {
    int observations = 0;
    int matched = 0;
  };
  const std::vector<Entry>& Ring() const { return ring_; }
  int Head() const { return head_; }
  void Restore(int capacity, std::vector<Entry> ring, int head, int size);

 private:
  int capacity_;
  std::vector<Entry> ring_;
  int head_ = 0;
  int size_ = 0;
  int observations_ = 0;
  int matched_ = 0;
};

enum class HypothesisState : uint8_t { kJuvenile = 0, kMature = 1, kRetired = 2 };
const char* HypothesisStateName(HypothesisState s);

// One step kept for the bootstrap function w (eq. 12): a laser scan, or a sonar reading when
// w solves from sonar (PoseBootstrapper::FromSonar; `observation` then holds an empty scan).
// The observation is the one the step gave the maps, with the lines they extracted from it.
struct JuvenileScan {
  Pose2 odometry_delta;  // motion from the previous step to this one, robot frame
  ScanObservation observation;
  ScanUpdate update;  // what the seeded juvenile made of it
  SonarReading sonar;
};

// kUndetermined: Z does not determine the pose yet (too few explained measurements, or a
// direction they leave free); the atlas keeps accumulating Z and calls w again at the next
// step, until the end of probation, when the juvenile is killed as for kFailed.
enum class BootstrapOutcome { kSolved, kFailed, kUndetermined };
struct PoseBootstrap {
  BootstrapOutcome outcome = BootstrapOutcome::kFailed;
  UncertainPose pose;  // the robot pose at the last step of Z, in the map's frame
  // M_i^new of eq. 12 when w makes one (it then replaces the juvenile's trial map, whose robot
  // pose is `pose`); null: the trial map is kept and its robot pose is reset to `pose`.
  std::unique_ptr<LocalMap> map;
};

// w of eq. 12: solves for the robot pose from the measurements Z alone, independently of the
// seed. `map` is the juvenile's map (its robot pose is the seed refined by the juvenile's own
// updates over Z); `frame_map` is M_i, the frame's map as the juvenile found it (the juvenile
// works on a clone, so it holds nothing of the seed); `seed` is x_i* of eq. 10-11 as the
// juvenile was seeded, before Z's first increment. w must not rely on either pose beyond
// proposing correspondences (and, for the sonar's w, gating the solution).
//
// w may also be solved in slices over several steps (Begin, then BootstrapSearch::Continue once
// per step), so that a search larger than a step's budget costs each step a bounded share
// (docs/design.md, "Constant time"). A sliced search solves for the pose at the last step of Z
// as it was at Begin; the atlas carries it to the current step by the odometry since.
class BootstrapSearch {
 public:
  virtual ~BootstrapSearch() = default;
  // One slice. `map`, `frame_map` and `z` as for Solve, now (z holds the steps it held at Begin
  // first). True when TakeResult() is final.
  virtual bool Continue(const LocalMap& map, const LocalMap& frame_map,
                        const std::vector<JuvenileScan>& z) = 0;
  // Once, when Continue returned true.
  virtual PoseBootstrap TakeResult() = 0;
};

class PoseBootstrapper {
 public:
  virtual ~PoseBootstrapper() = default;
  virtual PoseBootstrap Solve(const LocalMap& map, const LocalMap& frame_map,
                              const std::vector<JuvenileScan>& z,
                              const UncertainPose& seed) const = 0;
  // Solve in slices; the bootstrapper must outlive the search. Default: Solve at the first
  // Continue.
  virtual std::unique_ptr<BootstrapSearch> Begin(const LocalMap& map, const LocalMap& frame_map,
                                                 const std::vector<JuvenileScan>& z,
                                                 const UncertainPose& seed) const;
  // Whether Z holds the juvenile's sonar steps (true) or its laser steps (false, the default).
  virtual bool FromSonar() const { return false; }
};

struct Hypothesis {
  int64_t id = 0;
  FrameId frame = kNoFrame;
  HypothesisState state = HypothesisState::kJuvenile;
  bool dominant = false;
  int64_t born_step = 0;
  int steps = 0;          // scans processed
  double q = 0.0;         // eq. 5 after the latest scan
  int failing_steps = 0;  // consecutive steps with q < q_fail
  int lagging_steps = 0;  // consecutive steps with q < dominant q - retire_margin
  QualityWindow window;
  ScanUpdate last_update;
  // Juvenile only: private copy of the frame's map, and the bootstrap state.
  std::unique_ptr<LocalMap> trial_map;
  bool bootstrapped = false;
  std::vector<JuvenileScan> z;
  UncertainPose seed;  // x_i* of eq. 10-11 when seeded: the pose before z's first increment
  // w in progress (BootstrapSearch), begun when z held w_begun_at steps; not in the byte image.
  std::unique_ptr<BootstrapSearch> w_search;
  size_t w_begun_at = 0;
};

struct LifecycleOptions {
  // Probation (III-E, left open by the paper): scans a juvenile processes before it is judged.
  // At least bootstrap_scans + 3: w needs its scans, then q needs a few scans of the
  // bootstrapped pose so that the window reflects w's solution, not the seed. 20: fewer returns
  // left open and fewer gross map-match edges on the corrected logs than 8 to 16, at the cost
  // of 10-19 m of travel before a right juvenile matures where scans are 0.5-0.9 m apart
  // (docs/design.md, "III-B. Hypotheses").
  int probation_scans = 20;
  // Scans accumulated before w is solved (eq. 12).
  int bootstrap_scans = 4;
  double q_fail = 0.35;  // a mature hypothesis below this is failing
  int fail_steps = 3;    // ... for this many consecutive scans
  // A mature hypothesis other than the dominant one whose q is more than retire_margin below
  // the dominant's for lag_steps consecutive scans is retired (see the transitions above).
  // 0.2 and 15 scans (3 s at 5 scans/s): measured on the simulator's sonar atlases (alcove
  // corridor loop and building), neutral on the laser logs (docs/design.md, "III-B. Hypotheses").
  double retire_margin = 0.2;
  int lag_steps = 15;
  // Hysteresis of the dominant hypothesis: the one that dominated at the previous step stays
  // dominant while it is mature and its q is within switch_margin of the best q. A switch moves
  // the published pose into another hypothesis's estimate at once (docs/design.md, "III-B.
  // Hypotheses"); 0: the best q dominates at every step.
  double switch_margin = 0.0;
  std::string Validate() const;
  bool operator==(const LifecycleOptions&) const = default;
};

enum class JuvenileVerdict { kContinue, kMature, kDelete };

// Judges a juvenile after its latest scan. `best_mature_q` is the best q among mature
// hypotheses (negative when there is none). `bootstrap_failed` is w's outcome this step.
JuvenileVerdict JudgeJuvenile(const Hypothesis& h, double best_mature_q, bool bootstrap_failed,
                              const LifecycleOptions& options);

// Updates h.failing_steps from h.q and returns true when a mature hypothesis is failing.
bool UpdateFailing(Hypothesis* h, const LifecycleOptions& options);
// Updates h.lagging_steps from h.q and the dominant hypothesis's q (`h_is_dominant`: h is the
// dominant one, which never lags) and returns true when a mature hypothesis has lagged for
// lag_steps scans.
bool UpdateLagging(Hypothesis* h, bool h_is_dominant, double dominant_q,
                   const LifecycleOptions& options);

// The index of the dominant hypothesis, or -1: the best q among mature ones (ties to the older),
// unless the hypothesis flagged `dominant` (the previous step's) is mature and within
// `switch_margin` of that q (LifecycleOptions::switch_margin).
int DominantIndex(const std::vector<Hypothesis>& hypotheses, double switch_margin = 0.0);

}  // namespace atlas
