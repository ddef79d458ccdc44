#pragma once
// The Atlas framework's step (paper, Sections II-III): a graph of map-frames with a bounded set
// of competing hypotheses, Genesis, traversal, map-matching and edge refinement, in constant
// time per step. No I/O. The reasoning behind each part, and the choices the paper leaves open,
// are in docs/design.md (sections III-A to III-F, "Constant time").
//
// Step(odometry_delta, scan), in this order:
//  1. Every live hypothesis predicts and updates with the scan; q (eq. 5) is recomputed. A
//     juvenile bootstrapping keeps its scans, and after `lifecycle.bootstrap_scans` of them w
//     (eq. 12) solves its pose (killed if w fails; retried each step while undetermined).
//  2. Juveniles at the end of probation mature (q beats every mature hypothesis; the trial map
//     replaces the frame's map) or are deleted (Fig. 4); a deleted juvenile's frame is not
//     reseeded for `seed_cooldown_steps`.
//  3. Failing mature hypotheses (hypothesis.h; and one contradicting the dominant pose across
//     an edge beyond `refine_gate_chi2`) retire if another mature hypothesis is healthy; else
//     Genesis (III-C) starts a frame from the dominant one, unless juveniles are on probation.
//  4. Traversal (III-E, eq. 10-11): juveniles seeded in frames near the dominant one, bounded by
//     `traversal_max_hops`, `traversal_reach` and the return band (`return_q`).
//  5. Genesis at capacity (III-C).
//  6. Map-matching (III-D, map_match.h): at most `match_candidates_per_step` bounded searches
//     (cross-matches or uncached self-matches) per step; the projection only gates. With a
//     matcher (SetMapMatcher), one search at a time, carried over steps in slices
//     (map_matcher.h): a step continues the pending search, or begins candidates' searches
//     (those that end in their first slice count as above) until one stays pending; while one
//     is pending, map-matching and w (step 1) take turns, one slice per step.
//  7. Edge refinement (III-F, edge_refinement.h): at most `max_refinements_per_step`, Genesis
//     edges only unless `refine_map_match_edges`; observations outside the gate are rejected.
//
// Constant time: every loop is bounded by an option and the map capacity; none runs over all
// frames or edges. Memory per frame: its map, at most max_degree edges, its points, O(1) more.
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
#include "core/atlas/map_matcher.h"

namespace atlas {

// Defaults: atlasd's atlas of laser lines (config/atlasd.toml); SonarAtlasOptions for sonar lines.
struct AtlasOptions {
  HypothesisQualityOptions quality;
  LifecycleOptions lifecycle;
  // Condition 2 for maps of laser lines (map_match.h); SonarAtlasOptions has the sonar's.
  MapMatchOptions match = LaserMapMatchOptions();
  // Each frame keeps the laser endpoints of its mature hypotheses' scans (frame_points.h), and
  // map-matching asks them when the lines are ambiguous (map_match.h, "Points"). Off: no points.
  FramePointsOptions points;
  int max_hypotheses = 8;  // live hypotheses, juvenile and mature
  int max_degree = 16;     // edges per frame
  double q_traverse = 0.6;
  int max_seeds_per_step = 1;
  // w searches (eq. 12) begun or continued per step; a juvenile whose Z is due waits, its Z
  // growing, while the step's are spent. A sliced w (PoseBootstrapper::Begin) goes on over
  // steps.
  int max_bootstraps_per_step = 8;
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
  // dominant one, which still explains them well enough not to fall below q_traverse
  // (docs/design.md, "III-E. Traversal").
  double return_q = 0.9;
  double return_radius = 4.0;
  // In that band only, frames farther than `traversal_max_hops` edges (any frame of the
  // bounded projection) are seeded too when their origin lies within this many metres of the
  // seed: the robot is back where a frame began that the chain of Genesis edges has carried
  // far along the graph (docs/design.md, "III-E. Traversal"). Tighter than return_radius,
  // because the seed comes along a longer chain. 0: off.
  double return_far_radius = 1.5;
  // Bounded Dijkstra projection used by traversal and map-matching.
  int projection_max_frames = 24;
  double projection_max_rho = std::numeric_limits<double>::infinity();
  int match_candidates_per_step = 2;
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
  // Genesis (III-C) puts the robot's covariance in the old frame on the new edge, times this
  // (our addition; 1 = the paper). The local maps' covariance there is optimistic: on the six
  // corrected logs (30 seeds) the edges of the Genesis chain lie at a median chi-square of
  // 3.6-4.9 on four logs and 13.7 on freiburg-079 against the reference, where 2.37 is expected,
  // and a prior composed from them gates map-matching and seeds traversal (docs/design.md,
  // "III-C. Genesis"). 2: measured on the six corrected logs and mit-csail.
  double genesis_cov_scale = 2.0;
  double capacity_explanation = 0.8;
  int genesis_min_interval_steps = 5;
  // Matching into unconnected parts of the graph (after ResumeInNewFrame), no prior.
  int resume_candidates_per_step = 1;
  int resume_scan_per_step = 8;
  std::string Validate() const;  // empty when valid
  bool operator==(const AtlasOptions&) const = default;
};

// The atlas of maps of wide-beam sonar lines: `o` with SonarMapMatchOptions() for map-matching,
// without points (a sonar reading has no laser endpoints), with the paper's Genesis edge
// (genesis_cov_scale 1) and without the return band (return_q and return_far_radius 0): on
// the simulator's sonar atlases the band made the robot NEES and the false closures worse
// (docs/design.md, "III-E. Traversal"). The defaults above are the laser atlas's.
AtlasOptions SonarAtlasOptions(AtlasOptions o = {});

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
  // The dominant hypothesis is another than at the previous step: the pose moved to another
  // hypothesis's estimate (or frame) at once, not by the robot's motion.
  bool switched = false;
};

// Why Atlas::DeserializeWithFrameMaps did not load an image.
enum class ImageLoadStatus {
  kLoaded,
  kMalformed,          // not an image of this atlas (bytes, version, or a value out of range)
  kFrameMapMissing,    // `frame`'s map is neither in the image nor given
  kFrameMapMalformed,  // `frame`'s map as given does not decode with this atlas's factory
};

struct ImageLoadResult {
  ImageLoadStatus status = ImageLoadStatus::kMalformed;
  FrameId frame = kNoFrame;
  bool ok() const { return status == ImageLoadStatus::kLoaded; }
};

class Atlas {
 public:
  using MapFactory = std::function<std::unique_ptr<LocalMap>()>;

  // `options` must be valid and `factory` non-empty (programmer errors, asserted).
  Atlas(const AtlasOptions& options, MapFactory factory,
        std::shared_ptr<const PoseBootstrapper> bootstrapper);

  // Map-matching by `matcher` instead of the line matcher (map_matcher.h); null: the lines.
  void SetMapMatcher(std::shared_ptr<const MapMatcher> matcher) {
    matcher_ = std::move(matcher);
    pending_match_.reset();
  }

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
  // Version 6 lets the frames' maps be kept apart (SerializeWithoutFrameMaps); otherwise as 5.
  static constexpr uint32_t kImageVersion = 6;
  std::string Serialize() const;
  bool Deserialize(const std::string& bytes);
  // The image without the frames' maps, for a saver that keeps each frame's map apart
  // (Graph().Frame(f).map->Serialize(), written again when its map_revision changed): each
  // frame's map image is empty in it; the hypotheses' trial maps are in it. Its cost does not
  // grow with the maps: O(frames + edges) plus the frames' points and the hypotheses.
  std::string SerializeWithoutFrameMaps() const;
  // Frame f's map image kept apart from the atlas image, or null when there is none.
  using FrameMapImages = std::function<const std::string*(FrameId f)>;
  // Deserialize of an image with or without the frames' maps: a frame whose map is not in the
  // image takes `frame_maps(f)` (may be empty: every map must then be in the image). On failure
  // the atlas is unchanged and the result says why, naming the frame when its map was missing
  // or did not decode.
  ImageLoadResult DeserializeWithFrameMaps(const std::string& bytes,
                                           const FrameMapImages& frame_maps);

 private:
  // The map hypothesis h updates (the frame's map_revision changes when it is the frame's).
  LocalMap& MapOf(Hypothesis& h);
  std::string SerializeImage(bool frame_maps) const;
  // Exactly one of `scan`, `sonar` is non-null.
  // `increment_cov`: the increment's covariance, or null for the maps' odometry model.
  // Whether a step's input can be used (StepStats::rejected_input).
  static bool UsableInput(const Pose2& odometry_delta, const Mat3* increment_cov,
                          const LaserScan* scan, bool first);
  const StepStats& LocalizeWith(const Pose2& odometry_delta, const Mat3* increment_cov,
                                const LaserScan* scan, const SonarReading* sonar);
  void UpdateHypotheses(const Pose2& odometry_delta, const Mat3* increment_cov,
                        const LaserScan* scan, const SonarReading* sonar, bool first);
  // Applies w's result to hypothesis i (its trial map `map`); true when Z is kept for another
  // try (undetermined before the end of probation).
  bool UseBootstrap(int i, LocalMap& map, PoseBootstrap r);
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
  MapMatch MatchWithLines(FrameId dom_frame, FrameId other, const UncertainPose* prior);
  // Counts a match's outcome and adds its edge when accepted.
  void ApplyMatch(FrameId dom_frame, FrameId other, const MapMatch& m);
  // Runs this step's slice of the matcher's pending search, applying it when it ends. False
  // when there was none.
  bool ContinuePendingMatch();
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
  std::shared_ptr<const MapMatcher> matcher_;
  // The matcher's search in progress (map_matcher.h), between frames pending_a_ and pending_b_;
  // not part of the byte image (a loaded atlas starts without one).
  std::unique_ptr<MapMatchSearch> pending_match_;
  FrameId pending_a_ = kNoFrame, pending_b_ = kNoFrame;
  int w_searches_ = 0;  // w searches begun or continued this step
  AtlasGraph graph_;
  FrameComponents components_;
  uint64_t resume_cursor_ = 0;
  std::vector<Hypothesis> hypotheses_;
  int64_t step_ = 0;
  bool graph_pending_ = false;  // Localize() ran, MaintainGraph() not yet
  int64_t next_hypothesis_id_ = 0;
  int64_t previous_dominant_ = -1;  // the dominant hypothesis's id before this step, or -1
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
