#pragma once
// Map-matching between two line maps (paper, Section III-D, eq. 7-9), for loop closure. The
// forms of m and t, and why each Condition 2 check exists: docs/design.md, "III-D.
// Map-matching".
//
// Contract:
// - t is hypothesised from the maps alone (pairs of non-parallel lines whose angles agree),
//   never from the robot pose; the prior (the Dijkstra projection of B in A) only gates.
// - m is the support: lines of B that land inside the chi-square gate of a distinct line of A
//   with overlapping segments. Accepted only with `min_support` lines and a lead of `min_lead`
//   over every distinct rival transform inside the prior's gate.
// - Condition 2: self-matched repetitions inside the prior's gate are excluded and their rival
//   placements verified (kRepetitive); every matched pair must be redundant to
//   `redundancy_sigma` unless the prior is narrower than `redundancy_prior_halfwidth`
//   (kSinglePair); a nearly parallel alternative line that gives a placement more than
//   `alternative_sigmas` away, allowed by the other pairs and the prior, is kSinglePair too.
// - t's covariance: Gauss-Newton over the matched pairs, times n with
//   `unknown_line_correlation`; all-parallel matched lines are kRejected (kDegenerate).
// - Points (frame_points.h): a kRepetitive or kRivalTransform refusal is looked at again with
//   the frames' laser endpoints; the placement they single out (`point_min_hits`,
//   `point_rival_ratio`) is accepted, with t still from its lines and every check above.
// Cost: O(n^4) hypotheses over at most `max_lines` lines per map, each verified in O(n^2),
// bounded by the map capacity and by `max_line_checks`; a search (or self-match) cut short is
// kRejected (kWorkBound). The points' look adds a bounded number of placements, each scored over
// at most FramePointsOptions::max_scored cells. Independent of the atlas size.

#include <Eigen/LU>
#include <cstdint>
#include <string>
#include <vector>

#include "core/atlas/frame_points.h"
#include "core/geometry/se2.h"
#include "core/localmap/local_map.h"

namespace atlas {

struct MapMatchOptions {
  double min_line_length = 0.5;        // metres; shorter lines are not used
  int max_lines = 24;                  // longest lines used per map (<= 64)
  double parallel_tolerance = 0.25;    // rad; pairs closer to parallel do not hypothesise
  double pair_angle_tolerance = 0.06;  // rad; angle-between-lines agreement
  double line_gate_chi2 = 9.21;        // 2 dof, 99 %
  double sigma_rho_floor = 0.03;       // metres, added to every line's rho variance
  double sigma_alpha_floor = 0.01;     // rad
  double overlap_slack = 0.5;          // metres of allowed gap between matched segments
  int min_support = 3;                 // lines
  // A self-repetition excludes its lines only with at least this support (see above).
  int self_min_support = 3;
  int min_lead = 1;                   // lines the best must lead any distinct rival by
  double distinct_translation = 0.5;  // metres: transforms closer than this are the same
  double distinct_rotation = 0.1;     // rad
  double prior_gate_chi2 = 16.27;     // 3 dof, 99.9 %
  bool self_match = true;
  int64_t max_line_checks = 200000;  // work bound of one match or self-match (see above)
  int gauss_newton_iterations = 4;
  // t's covariance n (sum H^T S^-1 H)^-1 instead of (sum H^T S^-1 H)^-1 (see above).
  bool unknown_line_correlation = false;
  // Every matched pair must be redundant: without it, the other pairs fix t's translation to
  // this standard deviation (metres) in every direction (see above); 0 turns the test off.
  double redundancy_sigma = 1.0;
  // ... unless the prior's gate (prior_gate_chi2) along that direction reaches at most this far
  // (metres) either side: the prior then tells the pair's alternatives apart. 0: never.
  double redundancy_prior_halfwidth = 2.0;
  // Alternative lines (see above): a pair whose line could as well be paired with another
  // near-parallel line, at a placement more than this many sigmas of t's covariance away that
  // the other pairs and the prior both allow, makes the match kAmbiguous (kSinglePair). 0: off.
  double alternative_sigmas = 0.0;
  // Points (see above): the winning placement needs this many hits, and every rival placement
  // at most this share of the winner's hits (0.6 / 0.7 / 0.8 left 1638 / 1555 / 1539 returns
  // open over 60 seeds of the corrected logs, none false; 0.7 keeps a margin).
  int point_min_hits = 40;
  double point_rival_ratio = 0.7;
  // Points: the farthest shift (metres) searched along a direction one pair fixes; a prior
  // whose gate reaches farther leaves it unfixed. 10 m: a prior sigma of 2.5 m along it, at
  // most 2 x 100 placements of max_scored cells.
  double point_max_shift = 10.0;
  std::string Validate() const;
  bool operator==(const MapMatchOptions&) const = default;
};

// The Condition 2 settings for maps of laser lines (atlasd with a laser, atlas-replay): `o`
// with unknown_line_correlation and alternative_sigmas 3, redundancy_prior_halfwidth 1 m
// (default 2 m) and sigma_alpha_floor 0.02 rad (default 0.01). Why each, and what the defaults
// let through on the corrected logs: docs/design.md, "III-D. Map-matching".
MapMatchOptions LaserMapMatchOptions(MapMatchOptions o = {});

// The Condition 2 settings for maps of wide-beam sonar lines: `o` with redundancy_sigma 0.25 m
// and redundancy_prior_halfwidth 0.5 m (defaults 1 m / 2 m, laser 1 m / 1 m),
// alternative_sigmas 3, and unknown_line_correlation. Why: a sonar atlas's priors are less
// consistent than a laser atlas's, and its maps hold few lines across a corridor
// (docs/design.md, "III-D. Map-matching"). Used by atlasd (sensors = "sonar") and by
// tools/sonar_eval.
MapMatchOptions SonarMapMatchOptions(MapMatchOptions o = {});

enum class MapMatchResult { kAccepted, kRejected, kAmbiguous };
enum class MapMatchReason {
  kMatched,
  kTooFewLines,       // rejected: not enough usable structure
  kTooLittleSupport,  // rejected: no hypothesis reached min_support
  kDegenerate,        // rejected: matched lines do not fix the transform
  kOutsidePrior,      // rejected: the best transform contradicts the prior (Condition 2)
  kRepetitive,        // ambiguous: structure unique within the maps is too little
  kRivalTransform,    // ambiguous: a distinct transform is (nearly) as well supported
  kWorkBound,         // rejected: the search (or a self-match) was cut short by max_line_checks
  kSinglePair,        // ambiguous: one matched pair alone fixes a direction of t
  kFreeSpace,         // rejected: at t, one frame's walls stand in the other's observed free space
};
inline constexpr int kMapMatchReasonCount = 10;
const char* MapMatchResultName(MapMatchResult r);
const char* MapMatchReasonName(MapMatchReason r);

// Repetitive structure of one map, from matching it with itself.
struct SelfMatch {
  struct Repetition {
    Pose2 transform;     // S: maps the map onto itself
    uint64_t lines = 0;  // bit k: prepared line k takes part (as source or image)
    int support = 0;
  };
  std::vector<Repetition> repetitions;
  int usable_lines = 0;
  bool complete = true;  // false when max_line_checks cut the self-match short
};

struct MapMatch {
  MapMatchResult result = MapMatchResult::kRejected;
  MapMatchReason reason = MapMatchReason::kTooFewLines;
  UncertainPose b_in_a;  // t (eq. 9): the pose of B's frame in A's frame, with covariance
  int support = 0;
  int rival_support = 0;
  int hypotheses = 0;  // transform hypotheses verified (work done)
  // Points (see above): whether the points singled out the accepted placement, and the hits of
  // the best placement and of its best rival when the points were asked (-1: not asked, or no
  // placement to score).
  bool by_points = false;
  int point_hits = -1;
  int point_rival_hits = -1;
};

SelfMatch SelfMatchMap(const std::vector<MapLine>& lines, const MapMatchOptions& options);

// Matches map B into map A. `self_a`, `self_b` are the maps' self-matches (ignored when
// options.self_match is false). `prior_b_in_a`, if not null, is the Dijkstra projection of B's
// frame in A's frame, used only to gate (Condition 2), never to form t. `points_a`, `points_b`,
// if both set, are the frames' points, asked when the lines alone are ambiguous (see "Points").
MapMatch MatchMaps(const std::vector<MapLine>& a, const SelfMatch& self_a,
                   const std::vector<MapLine>& b, const SelfMatch& self_b,
                   const UncertainPose* prior_b_in_a, const MapMatchOptions& options,
                   const FramePoints* points_a = nullptr, const FramePoints* points_b = nullptr);

}  // namespace atlas
