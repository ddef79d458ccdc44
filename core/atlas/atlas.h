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
//     pose is replaced by w's solution, or the juvenile is killed if w fails.
//  2. Juveniles at the end of probation mature (q beats every mature hypothesis) or are deleted
//     (Fig. 4). The frame of a deleted juvenile is not reseeded for `seed_cooldown_steps`.
//  3. Failing mature hypotheses (q < q_fail for fail_steps scans) are retired if another mature
//     hypothesis is healthy. If none is, Genesis (III-C) starts a new frame from the dominant
//     one and the failing ones retire, unless juveniles are still on probation (they get their
//     probation first: a known place must win over a new frame when the robot returns).
//  4. Traversal (III-E, eq. 10-11): when the dominant q is below q_traverse, juveniles are
//     seeded in frames near the dominant frame (bounded Dijkstra projection, at most
//     `traversal_max_hops` edges away, nearest in rho first) that carry no hypothesis:
//     x_i* = T_i^d (+) x_d with T_i^d the pose of the dominant frame in frame i composed along
//     the projection tree (one edge for adjacent frames, exactly eq. 10-11).
//  5. Genesis at capacity (III-C): the dominant map is full, its q is below q_traverse, it
//     explains less than `capacity_explanation` of its recent observations (it would have to
//     grow), no other
//     mature hypothesis sits in a frame that can still grow, and no juvenile is alive (known
//     frames nearby get their probation before a new frame competes with them).
//  6. Map-matching (III-D): candidates are the frames of the bounded projection from the
//     dominant frame that are not adjacent to it, whose origin lies within `match_radius` of
//     the robot (plus 3 sigma of the projection), with enough lines. At most
//     `match_candidates_per_step` are matched per step, round-robin over the candidates, so the
//     search is spread over steps; a pair is not re-matched until one of its maps changed. The
//     projection (prior) only gates (Condition 2); t comes from the maps (map_match.h).
//  7. Edge refinement (III-F): for mature hypotheses in adjacent frames, covariance
//     intersection (edge_refinement.h), at most `max_refinements_per_step`, each edge at most
//     once per `refine_interval_steps`.
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

#include <functional>
#include <memory>
#include <string>
#include <vector>

#include "core/atlas/atlas_graph.h"
#include "core/atlas/dijkstra_projection.h"
#include "core/atlas/hypothesis.h"
#include "core/atlas/map_match.h"

namespace atlas {

struct AtlasOptions {
  HypothesisQualityOptions quality;
  LifecycleOptions lifecycle;
  MapMatchOptions match;
  int max_hypotheses = 4;  // live hypotheses, juvenile and mature
  int max_degree = 16;     // edges per frame
  double q_traverse = 0.6;
  int max_seeds_per_step = 1;
  int seed_cooldown_steps = 20;
  int traversal_max_hops = 2;
  // Bounded Dijkstra projection used by traversal and map-matching.
  int projection_max_frames = 24;
  double projection_max_rho = std::numeric_limits<double>::infinity();
  int match_candidates_per_step = 1;
  int match_interval_steps = 1;
  int min_match_lines = 4;
  double match_radius = 10.0;  // metres
  int self_match_cache = 16;   // frames whose self-match is kept
  int match_memory = 64;       // recently matched pairs remembered (not re-matched unchanged)
  int max_refinements_per_step = 1;
  int refine_interval_steps = 10;
  double capacity_explanation = 0.8;
  int genesis_min_interval_steps = 5;
  std::string Validate() const;  // empty when valid
};

struct StepStats {
  int64_t step = 0;
  int frames = 0;
  int hypotheses_alive = 0;
  int frames_examined = 0;  // projection entries settled this step
  int candidates_matched = 0;
  int match_hypotheses = 0;  // transform hypotheses verified by map-matching
  int seeded = 0, matured = 0, deleted = 0, retired = 0, killed_by_w = 0;
  int bootstraps = 0;
  int genesis = 0;
  int genesis_refused = 0;  // the dominant frame's degree was full
  int match_accepted = 0, match_rejected = 0, match_ambiguous = 0;
  int refined = 0;
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

  // One step: `odometry_delta` is the motion since the previous scan (robot frame at the
  // previous scan; ignored on the very first step), `scan` the new scan.
  const StepStats& Step(const Pose2& odometry_delta, const LaserScan& scan);

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
  static constexpr uint32_t kImageVersion = 1;
  std::string Serialize() const;
  bool Deserialize(const std::string& bytes);

 private:
  LocalMap& MapOf(Hypothesis& h);
  void UpdateHypotheses(const Pose2& odometry_delta, const LaserScan& scan, bool first);
  void JudgeJuveniles();
  void HandleFailures();
  void GenesisAtCapacity();
  bool Genesis(int from_index);
  bool MakeRoomForHypothesis(int keep_index);
  int FindDominant();
  bool HasHypothesis(FrameId f) const;
  const Projection& ProjectionFromDominant(FrameId dominant);
  void Traverse(int dominant);
  void MatchMaps(int dominant);
  void RefineEdges();
  const SelfMatch& SelfMatchOf(FrameId f);

  AtlasOptions options_;
  MapFactory factory_;
  std::shared_ptr<const PoseBootstrapper> bootstrapper_;
  AtlasGraph graph_;
  std::vector<Hypothesis> hypotheses_;
  int64_t step_ = 0;
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
