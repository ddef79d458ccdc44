#pragma once
// The Atlas framework's step (paper, Sections II-III): a graph of map-frames with a bounded set
// of competing hypotheses, Genesis, traversal, map-matching and edge refinement, in constant
// time per step. No I/O.
//
// Step(odometry_delta, scan), in this order:
//  1. Every live hypothesis predicts with the odometry increment and updates with the scan
//     (mature: may add features; juvenile: may not, and works on a private clone of its frame's
//     map). q (eq. 5) is recomputed. A juvenile still bootstrapping keeps its scans; after
//     `lifecycle.bootstrap_scans` of them, w (eq. 12) solves its pose from the scans alone: the
//     pose is replaced by w's solution (and the trial map by w's M_i^new when w makes one),
//     or the juvenile is killed if w fails. While w is undetermined (Z does not fix the pose
//     yet) Z keeps growing and w is tried at every step until the end of probation.
//  2. Juveniles at the end of probation mature (q beats every mature hypothesis) or are deleted
//     (Fig. 4). The frame of a deleted juvenile is not reseeded for `seed_cooldown_steps`.
//     The matured juvenile's trial map replaces the frame's map. Without w (no bootstrapper:
//     the sonar atlas) `keep_frame_map_without_w` instead keeps the frame's map and gives it
//     the juvenile's robot pose (an experiment, off: docs/sonar.md, session 7).
//  3. Failing mature hypotheses (q < q_fail for fail_steps scans, or, other than the dominant
//     one, q more than retire_margin below the dominant's for lag_steps scans: hypothesis.h) are
//     retired if another mature hypothesis is healthy. If none is, Genesis (III-C) starts a new
//     frame from the dominant one and the failing ones retire, unless juveniles are still on
//     probation (they get their probation first: a known place must win over a new frame when the
//     robot returns). A mature hypothesis in a frame adjacent to the dominant one whose pose
//     contradicts the dominant pose across their edge (ContradictsDominant: the edge
//     observation of eq. 14-15 outside `refine_gate_chi2`) counts as failing at once (our
//     addition): both track the same robot, so one of them is lost, and the dominant one is
//     the output. On mit-csail such lost hypotheses took over as dominant with 5-20 m errors.
//  4. Traversal (III-E, eq. 10-11): when the dominant q is below q_traverse, juveniles are
//     seeded in frames near the dominant frame (bounded Dijkstra projection, at most
//     `traversal_max_hops` edges away, nearest in rho first) that carry no hypothesis and
//     have a line within `traversal_reach` of the seed:
//     x_i* = T_i^d (+) x_d with T_i^d the pose of the dominant frame in frame i composed along
//     the projection tree (one edge for adjacent frames, exactly eq. 10-11).
//     With `return_q` above q_traverse, a dominant q in [q_traverse, return_q) seeds too, but
//     only frames whose origin lies within `return_radius` of the seed, and frames more than
//     `traversal_max_hops` edges away (still within the projection) whose origin lies within
//     `return_far_radius` of it (see the options).
//  5. Genesis at capacity (III-C): the dominant map is full, its q is below q_traverse, it
//     explains less than `capacity_explanation` of its recent observations (it would have to
//     grow), no other
//     mature hypothesis sits in a frame that can still grow, and no juvenile is alive (known
//     frames nearby get their probation before a new frame competes with them).
//  6. Map-matching (III-D): candidates are the frames of the bounded projection from the
//     dominant frame that are not adjacent to it, whose origin lies within `match_radius` of
//     the robot (plus 3 sigma of the projection), with enough lines. At most
//     `match_candidates_per_step` are matched per step, round-robin over the candidates, so the
//     search is spread over steps; a pair is not re-matched until one of its maps changed. A
//     self-match (map_match.h) that is not cached counts as one of those searches: it is
//     computed in this step and the pair matched in a later one, so that a step does at most
//     `match_candidates_per_step` bounded searches of either kind (each bounded by
//     match.max_line_checks), never a self-match of each map and a cross-match at once. The
//     projection (prior) only gates (Condition 2); t comes from the maps (map_match.h).
//     After ResumeInNewFrame() the graph has unconnected parts; their frames are matched
//     without a prior (at most `resume_candidates_per_step`, see ResumeInNewFrame).
//  7. Edge refinement (III-F): for mature hypotheses in adjacent frames, covariance
//     intersection (edge_refinement.h), at most `max_refinements_per_step`, each edge at most
//     once per `refine_interval_steps`. An observation that disagrees with the edge beyond
//     `refine_gate_chi2` is rejected (RefineEdge), not fused. Only edges made by Genesis are
//     refined unless `refine_map_match_edges` (our choice): a map-match edge's t comes from the
//     two maps alone (eq. 9), while the observation of eq. 14-15 comes from the hypotheses'
//     robot poses, which on the sonar alcove loop and intel were less consistent than the
//     maps; fused in, they made 2 true sonar closures and 1 laser one false (docs/atlas.md).
//
// Constant time: every loop above is bounded by an option (hypotheses alive, projection frames,
// seeds, candidates, refinements) and by the map capacity; no loop runs over all frames or
// edges. Memory per frame: its map (bounded by capacity) and at most max_degree edges, plus
// O(1) bookkeeping. The graph grows by one frame per Genesis.
//
// Choices the paper leaves open (all configurable):
// - probation length: 8 scans, bootstrap after 4 (hypothesis.h says why);
// - form of m and t: line-pair hypotheses verified by Mahalanobis gating (map_match.h);
// - q thresholds: q_traverse 0.6 (traversal starts while the map still mostly explains the data,
//   so juveniles have their probation before the dominant fails), q_fail 0.35;
// - a juvenile is seeded from the dominant hypothesis only (the output), not from every mature
//   one, which keeps seeding O(max_seeds_per_step).
//
// Errors: Step never throws; construction needs valid options (Validate()) and a map factory.
// Without a bootstrapper (w), juveniles keep their seeded pose and are judged on q alone.

#include <array>
#include <functional>
#include <memory>
#include <string>
#include <vector>

#include "core/atlas/atlas_graph.h"
#include "core/atlas/dijkstra_projection.h"
#include "core/atlas/frame_components.h"
#include "core/atlas/hypothesis.h"
#include "core/atlas/map_match.h"

namespace atlas {

struct AtlasOptions {
  HypothesisQualityOptions quality;
  LifecycleOptions lifecycle;
  MapMatchOptions match;
  // Each frame keeps the laser endpoints of its mature hypotheses' scans (frame_points.h), and
  // map-matching asks them when the lines are ambiguous (map_match.h, "Points"). Off: no points.
  FramePointsOptions points;
  int max_hypotheses = 4;  // live hypotheses, juvenile and mature
  int max_degree = 16;     // edges per frame
  double q_traverse = 0.6;
  int max_seeds_per_step = 1;
  int seed_cooldown_steps = 20;
  int traversal_max_hops = 2;
  // Traversal seeds a frame only when the seeded position lies within this distance (plus 3
  // sigma of the seed) of one of the frame's line segments: a map whose lines are all farther
  // than the sensor reaches cannot explain the scans, and its juvenile would only take a
  // hypothesis slot and the step's seed. Metres; default the laser range the maps use.
  double traversal_reach = 8.0;
  // Traversal where the robot returns (our addition; off when return_q <= q_traverse): while
  // the dominant q lies in [q_traverse, return_q), juveniles are seeded as in step 4, but only
  // in frames whose origin the seeded position lies within `return_radius` metres of: the
  // robot is back where that frame began, and its map may explain the scans better than the
  // dominant one, which still explains them well enough not to fall below q_traverse (a
  // square loop whose frame also covers the start: seattle, docs/atlas.md session 16).
  double return_q = 0.0;
  double return_radius = 4.0;
  // In that band only, frames farther than `traversal_max_hops` edges (any frame of the
  // bounded projection) are seeded too when their origin lies within this many metres of the
  // seed: the robot is back where a frame began that the chain of Genesis edges has carried
  // far along the graph (freiburg-079 gains most; docs/atlas.md session 18). Tighter than
  // return_radius, because the seed comes along a longer chain. 0: off.
  double return_far_radius = 0.0;
  // Bounded Dijkstra projection used by traversal and map-matching.
  int projection_max_frames = 24;
  double projection_max_rho = std::numeric_limits<double>::infinity();
  int match_candidates_per_step = 1;
  int match_interval_steps = 1;
  int min_match_lines = 4;
  double match_radius = 10.0;  // metres
  int self_match_cache = 32;   // frames whose self-match is kept (> the candidates of a step)
  int match_memory = 64;       // recently matched pairs remembered (not re-matched unchanged)
  int max_refinements_per_step = 1;
  int refine_interval_steps = 10;
  // Edge refinement gate (edge_refinement.h): chi-square, 3 dof; 16.27 = 99.9 %.
  double refine_gate_chi2 = 16.27;
  // Whether edges made by map-matching are refined too (step 7).
  bool refine_map_match_edges = false;
  // Step 2 without w: the trial map's features were updated from the seed x_i* of eq. 10-11,
  // which comes from other frames and the edges but enters the EKF as independent of frame i's
  // features, so adopting them fuses that seed into the frame's map at each re-entry. On:
  // the frame keeps its own map and takes the juvenile's robot pose (with no correlation to
  // the features, so later updates count the map's information twice instead). Measured on the
  // simulator's sonar atlases (docs/sonar.md, session 7): building NEES 9.59 -> 12.28, alcove
  // loop 6.91 -> 6.34; so off.
  bool keep_frame_map_without_w = false;
  // Without w: traversal seeds (eq. 10-11) get their covariance times this factor. The seed's
  // correlation with frame i's map is unknown (dropped with the frames' independence); a factor
  // 1/omega is the seed's side of covariance intersection (eq. 16-18) with weight omega. An
  // experiment (docs/sonar.md, session 7); 1 = the plain projection.
  double seed_cov_scale_without_w = 1.0;
  // Genesis (III-C) puts the robot's covariance in the old frame on the new edge, times this
  // (our addition; 1 = the paper). The local maps' covariance there is optimistic: on the six
  // corrected logs (30 seeds) the edges of the Genesis chain lie at a median chi-square of
  // 3.6-4.9 on four logs and 13.7 on freiburg-079 against the reference, where 2.37 is expected
  // (docs/atlas.md, session 17), and a prior composed from them gates map-matching and seeds
  // traversal. atlasd's laser atlas uses 2.
  double genesis_cov_scale = 1.0;
  double capacity_explanation = 0.8;
  int genesis_min_interval_steps = 5;
  // Matching into unconnected parts of the graph (after ResumeInNewFrame), no prior.
  int resume_candidates_per_step = 1;
  int resume_scan_per_step = 8;
  std::string Validate() const;  // empty when valid
};

// The largest odometry translation one step may carry (metres); more is a fault of the
// odometry, not motion (StepStats::rejected_input).
inline constexpr double kMaxStepTranslation = 1000.0;

struct StepStats {
  int64_t step = 0;
  int frames = 0;
  int hypotheses_alive = 0;
  int frames_examined = 0;  // projection entries settled this step
  int candidates_matched = 0;
  int self_matches = 0;      // self-matches computed (each one bounded search, as a cross-match)
  int match_hypotheses = 0;  // transform hypotheses verified by map-matching
  int seeded = 0, matured = 0, deleted = 0, retired = 0, killed_by_w = 0;
  int seeds_out_of_reach = 0;  // traversal candidates skipped: no line within traversal_reach
  int bootstraps = 0;
  int genesis = 0;
  int genesis_refused = 0;  // the dominant frame's degree was full
  int match_accepted = 0, match_rejected = 0, match_ambiguous = 0;
  int match_unconnected = 0;  // candidates from unconnected parts (no prior) matched this step
  int match_by_points = 0;    // accepted matches the frames' points singled out (map_match.h)
  // Map-matching outcomes this step by MapMatchReason (index static_cast<int>(reason)); an
  // accepted match whose edge could not be added counts as kMatched and as match_rejected.
  std::array<int, kMapMatchReasonCount> match_reasons{};
  int refined = 0;
  // 1 when this step's input could not be used and nothing was updated (Atlas::Step): its
  // odometry is not finite or moves more than kMaxStepTranslation, its increment covariance
  // is not finite, or the scan's sensor mounting is not finite. The motion of such a step is
  // lost; NaN must never reach a map, which it would poison for good.
  int rejected_input = 0;
  // Refinement observations outside the gate (a hypothesis disagrees with the edge), and mature
  // hypotheses retired for contradicting the dominant one across an edge.
  int refine_rejected = 0;
  int contradicting = 0;
  FrameId dominant_frame = kNoFrame;
};

struct DominantOutput {
  bool valid = false;
  int64_t hypothesis = -1;
  FrameId frame = kNoFrame;
  UncertainPose pose;  // robot pose in `frame`
  double q = 0.0;
};

class Atlas {
 public:
  using MapFactory = std::function<std::unique_ptr<LocalMap>()>;

  // `options` must be valid and `factory` non-empty (programmer errors, asserted).
  Atlas(const AtlasOptions& options, MapFactory factory,
        std::shared_ptr<const PoseBootstrapper> bootstrapper);

  // One step: `odometry_delta` is the motion since the previous measurement (robot frame at the
  // previous measurement; ignored on the very first step), `scan` the new scan.
  const StepStats& Step(const Pose2& odometry_delta, const LaserScan& scan);
  // The same step with a sonar ring reading (LocalMap::UpdateWithSonar) instead of a scan, for
  // sonar-only and laser-and-sonar robots. w (eq. 12) bootstraps juveniles from the steps of
  // the sensor it solves from (PoseBootstrapper::FromSonar: sonar readings for the sonar w,
  // core/sonar/sonar_map_bootstrapper.h; laser scans otherwise). Without a bootstrapper, a
  // juvenile counts as bootstrapped after `lifecycle.bootstrap_scans` steps of either kind and
  // is judged on q alone.
  const StepStats& Step(const Pose2& odometry_delta, const SonarReading& reading);

  // The same step in two halves, for a daemon that publishes the pose as early as it can:
  // Localize() runs steps 1-5 above (hypotheses, juveniles, failures, traversal, Genesis), after
  // which Dominant() is this step's output; MaintainGraph() runs steps 6-7 (map-matching, edge
  // refinement), which add or change edges but never change a hypothesis, so Dominant() is the
  // same after it. Step() == Localize() then MaintainGraph(). Every Localize() must be followed
  // by one MaintainGraph() before the next Localize() (asserted); the returned stats are
  // complete after MaintainGraph().
  const StepStats& Localize(const Pose2& odometry_delta, const LaserScan& scan);
  const StepStats& Localize(const Pose2& odometry_delta, const SonarReading& reading);
  // With the increment's covariance given (LocalMap::Predict(u, Q)), e.g. a scan-matched
  // increment (core/scanmatch/scan_matcher.h), instead of each map's odometry noise model.
  const StepStats& Localize(const UncertainPose& increment, const LaserScan& scan);
  const StepStats& MaintainGraph();

  // After Deserialize() of a saved atlas: the robot is somewhere unknown, so every hypothesis
  // is dropped and the robot starts in a new frame, unconnected, at pose exactly zero (as after
  // Genesis). Map-matching then also tries frames of the unconnected old parts, without a prior
  // (`resume_candidates_per_step` per step, a cursor over the frame ids, at most
  // `resume_scan_per_step` ids looked at per step), and the first accepted match joins them.
  // Returns the new frame's id.
  FrameId ResumeInNewFrame();

  DominantOutput Dominant() const;
  const AtlasGraph& Graph() const { return graph_; }
  const std::vector<Hypothesis>& Hypotheses() const { return hypotheses_; }
  const StepStats& LastStats() const { return stats_; }
  int64_t StepCount() const { return step_; }
  const AtlasOptions& Options() const { return options_; }
  // The robot pose of a live hypothesis (juveniles: in their trial map).
  UncertainPose PoseOf(const Hypothesis& h) const;

  // A versioned byte image of the whole atlas (graph, maps, hypotheses, bookkeeping).
  // Deserialize uses this atlas's factory to make maps; on bytes that are not a valid image it
  // returns false and leaves the atlas unchanged.
  // Version 2 added Hypothesis::lagging_steps; version 1 images are read with it zero.
  // Version 3 added JuvenileScan::sonar; older images are read with it empty.
  // Version 4 added Hypothesis::seed; an older image's juvenile takes its current pose as the
  // seed and starts its Z again.
  // Version 5 added each frame's points (FramePoints); older images are read with none.
  static constexpr uint32_t kImageVersion = 5;
  std::string Serialize() const;
  bool Deserialize(const std::string& bytes);

 private:
  LocalMap& MapOf(Hypothesis& h);
  // Exactly one of `scan`, `sonar` is non-null.
  // `increment_cov`: the increment's covariance, or null for the maps' odometry model.
  // Whether a step's input can be used (StepStats::rejected_input).
  static bool UsableInput(const Pose2& odometry_delta, const Mat3* increment_cov,
                          const LaserScan* scan, bool first);
  const StepStats& LocalizeWith(const Pose2& odometry_delta, const Mat3* increment_cov,
                                const LaserScan* scan, const SonarReading* sonar);
  void UpdateHypotheses(const Pose2& odometry_delta, const Mat3* increment_cov,
                        const LaserScan* scan, const SonarReading* sonar, bool first);
  void JudgeJuveniles();
  void HandleFailures();
  void GenesisAtCapacity();
  bool Genesis(int from_index);
  bool MakeRoomForHypothesis(int keep_index);
  int FindDominant();
  bool ContradictsDominant(const Hypothesis& dominant, const Hypothesis& h) const;
  bool HasHypothesis(FrameId f) const;
  const Projection& ProjectionFromDominant(FrameId dominant);
  void Traverse(int dominant);
  void MatchMaps(int dominant);
  void MatchUnconnected(int dominant);
  // Matches the dominant map with frame `other` (prior: its projected pose, or none) and adds
  // the edge when accepted.
  void MatchPair(FrameId dom_frame, FrameId other, const UncertainPose* prior);
  FrameId AddFrame(std::unique_ptr<LocalMap> map);
  // A new frame without edges, robot at exactly zero, one mature hypothesis in it.
  FrameId StartUnconnectedFrame();
  AddEdgeResult AddEdge(FrameId a, FrameId b, const UncertainPose& b_in_a, EdgeKind kind);
  void RefineEdges();
  const SelfMatch& SelfMatchOf(FrameId f);
  // The cached self-match of `f` at its current complexity, or nullptr.
  const SelfMatch* CachedSelfMatchOf(FrameId f) const;
  // Whether the pair was matched at the maps' current complexities (a recent pair is not
  // re-matched until one of its maps changed), and remembering that it was.
  bool TriedUnchanged(FrameId a, FrameId b) const;
  void RememberTried(FrameId a, FrameId b);
  bool WithinReach(const LocalMap& map, const UncertainPose& seed) const;
  // Computes the first of the two frames' self-matches that is not cached and returns true (the
  // step's search was spent on it), or returns false when both are cached.
  bool SpendSearchOnSelfMatch(FrameId a, FrameId b);
  // Bounded searches done this step: cross-matches and self-matches.
  int Searches() const { return stats_.candidates_matched + stats_.self_matches; }

  AtlasOptions options_;
  MapFactory factory_;
  std::shared_ptr<const PoseBootstrapper> bootstrapper_;
  AtlasGraph graph_;
  FrameComponents components_;
  uint64_t resume_cursor_ = 0;
  std::vector<Hypothesis> hypotheses_;
  int64_t step_ = 0;
  bool graph_pending_ = false;  // Localize() ran, MaintainGraph() not yet
  int64_t next_hypothesis_id_ = 0;
  int64_t last_genesis_step_ = -1000000;
  uint64_t match_cursor_ = 0;
  StepStats stats_;
  std::vector<uint8_t> bootstrap_failed_;  // per hypothesis, this step
  // Scratch, reused (no per-step allocation once warm).
  DijkstraWorkspace workspace_;
  Projection projection_;
  int64_t projection_step_ = -1;
  FrameId projection_source_ = kNoFrame;
  std::vector<FrameId> candidates_;
  struct CachedSelfMatch {
    FrameId frame = kNoFrame;
    int complexity = -1;
    SelfMatch self;
  };
  std::vector<CachedSelfMatch> self_cache_;
  int self_cache_next_ = 0;
  struct TriedPair {
    FrameId a = kNoFrame, b = kNoFrame;
    int complexity_a = -1, complexity_b = -1;
  };
  std::vector<TriedPair> tried_;
  int tried_next_ = 0;
};

}  // namespace atlas
