#pragma once
// Map-matching between two line maps (paper, Section III-D, eq. 7-9), for loop closure.
//
// The paper leaves the forms of m (eq. 7-8) and t (eq. 9) open. Choices made here:
// - t, the transform, is hypothesised from the maps alone (never from the robot pose): for a
//   pair of non-parallel lines (i, j) of map A and a pair (k, l) of map B whose angles agree
//   (the angle between two lines is invariant under SE(2)), aligning k with i and l with j
//   fixes the rotation (two solutions, theta and theta + pi, since a line's normal direction is
//   not invariant) and the translation (two line equations, non-parallel so solvable).
// - m, the degree of match, is the support of a hypothesis: the number of lines of B that,
//   transformed into A, fall within the chi-square gate of a distinct line of A (Mahalanobis
//   over (rho, alpha) with both lines' covariances) and whose segments overlap (with slack).
//   A match needs `min_support` lines and a support that leads every distinct rival transform
//   by `min_lead` lines: a unique best.
// - Self-match (III-D: "only structure elements that match uniquely within a map"): each map is
//   matched with itself; a non-identity self-transform S with at least `self_min_support` lines
//   is repetitive structure, and its lines are excluded. Condition 2: a repetition only matters
//   when the prior (the Dijkstra projection of B in A) cannot tell S (+) T from T, i.e. when
//   S (+) T lies inside the prior's gate; without a prior every repetition matters. The same
//   gate filters cross-match rivals. When exclusion leaves too little structure, or two
//   distinct transforms inside the gate are equally supported, the result is kAmbiguous.
//   After that, each remaining repetition's rival placement S (+) T (or T (+) S_b) inside the
//   gate is verified on the usable lines, and one that explains B within `min_lead` lines as
//   well as T does also makes the result kAmbiguous (kRepetitive). (Tried on 2026-11-23: using
//   only these verified rivals, without the exclusion, closes many more loops on the corrected
//   logs but accepts a wrong period in a repetitive corridor when the shifted placement
//   overlaps more of B than the true one: core/sonar/sonar_condition2_test.cc.)
// - Condition 2 per direction (redundancy): every matched pair must be redundant, i.e. the
//   other pairs alone fix t's translation to `redundancy_sigma` in every direction. A direction
//   fixed by one pair only (in a corridor: two walls and a single jamb, or one wall and jambs)
//   rests on a correspondence nothing else checks: any other line of that orientation would do
//   as well, and t's covariance, from that pair's own covariance, says nothing about the
//   choice. Such a match is kAmbiguous (kSinglePair), unless the prior's gate along that
//   direction reaches no further than `redundancy_prior_halfwidth` either side (Condition 2:
//   the prior tells the alternatives apart). On the sonar alcove loop (tools/sonar_eval, seeds
//   1-20) every gross false closure (2.3-2.4 m along or across the corridor, d2 > 1000) was
//   of this kind; the sonar atlas's priors are themselves inconsistent, so it uses 0.5 m
//   (sonar_eval::SonarAtlasOptions; 1-2 m let gross ones back). The default 2 m left the six
//   corrected laser logs' closures as they were (0.5 m refused 2 of intel's 4 true ones); laser
//   lines use 1 m since a 1.7 m alternative was accepted on csail (LaserMapMatchOptions).
// - Condition 2 against alternative lines: the redundancy test above asks whether the other
//   pairs fix a direction to an absolute redundancy_sigma; the maps themselves say which
//   alternatives there are. For each matched pair (i of A, k of B), every other line of A
//   nearly parallel to i (within parallel_tolerance) that k could lie on instead, and every
//   other line of B nearly parallel to k that could lie on i, gives a placement t' = t + shift
//   (t's rotation, translation moved along the alternative's normal). If the shift exceeds
//   `alternative_sigmas` standard deviations of t's covariance along it (smaller shifts are
//   what the covariance already allows), the two segments lie side by side at t'
//   (overlap_slack), t' lies inside the prior's gate, and every other pair stays inside its
//   line gate at t', then neither the other pairs nor the prior tell t from t': kAmbiguous
//   (kSinglePair). The case that made this test (freiburg-079, edge 8-0, 2026-11-23 session 6,
//   docs/atlas.md): a wall with a 0.4 m step; frame 8's map held both faces (a 4.8 m line and
//   a 1 m one, 0.09 rad apart), frame 0's map only the recessed one, which the match paired
//   with the 4.8 m line. That pair alone fixed t's x (sigma 0.105 m with it, 0.44 m without:
//   "redundant" by the 1 m test), and t came out 0.40 m off the reference (d2 18.7); the three
//   other pairs and the prior allowed the true placement as well. atlasd turns it on (3 sigma)
//   for laser lines (LaserMapMatchOptions), SonarMapMatchOptions for sonar lines;
//   off by default.
// - t's covariance comes from the matched lines' covariances: Gauss-Newton over all matched
//   pairs, Sigma = (sum H^T S^-1 H)^-1. The lines of one local map are correlated (they share
//   the robot's errors when they were seen) and MapLine carries only each line's marginal, so
//   this is optimistic; `unknown_line_correlation` scales it by n for n pairs (covariance
//   intersection with equal weights, eq. 16 with omega = 1/n), consistent whatever the
//   correlation. It is off by default: on the six corrected logs it cut the edges beyond 3
//   sigma of the reference (11 of 31 -> 2 of 57, gross 4 -> 1), but the looser edges widen the
//   Dijkstra projection's priors, and in the seeded sonar run on a repetitive corridor
//   (tools/sonar_eval SonarAtlasCondition2) a wrong period then passed the prior gate
//   (session 5). atlasd turns it on for laser lines (LaserMapMatchOptions) and, since session
//   16, for sonar ones (SonarMapMatchOptions: measured there). Matched
//   lines that are all parallel leave a singular information matrix: kRejected (degenerate),
//   never a guess.
// - Points (our addition; frame_points.h). Ten lines of a building of long corridors often
//   repeat within the map (a shift of one corridor width or door spacing), and then the match
//   is refused as kRepetitive or kRivalTransform above. On the corrected aces log that was 65 %
//   of all tries, and one was accepted in 60 seeds (docs/atlas.md, sessions 20 and 21). When
//   both frames keep the laser endpoints their maps were built from, such a refusal is looked
//   at again:
//   - every transform hypothesised from all lines (repeated ones included) that is inside the
//     prior's gate and has `min_support` lines is a placement;
//   - so is each repetition of the best of them (S (+) T, T (+) S_b), as above;
//   - each placement is scored by the cells of B's points that land next to cells of A's;
//   - the placement with the most hits is accepted only if it has `point_min_hits` of them
//     and no other placement reaches `point_rival_ratio` of its hits. Only structure that is
//     unique within the maps (III-D) can make that difference: door jambs, furniture, wall ends
//     and clutter that never became lines. Points that repeat as the lines do leave the
//     refusal standing (Condition 2);
//   - t and its covariance come from the lines of the chosen placement as above, and the
//     checks that follow stay. A direction that one pair alone fixes passes only if the points
//     fix it too: every shift along it of at least `distinct_translation`, out to the prior's
//     gate, has at most `point_rival_ratio` of t's hits. A gate reaching farther than
//     `point_max_shift` along it leaves the direction unfixed (the search is one Hits() per
//     cell of shift, so this bounds it). An alternative line's placement is dismissed the
//     same way.
//   The points never form t. Measured over 60 seeds of the six corrected logs (session 21): aces
//   went from 585 to 336 open returns, all six from 1805 to 1555, with no false closure. A search
//   along one pair of parallel lines by the points alone, for maps that share no two
//   non-parallel lines, was tried and dropped: it added 2 false closures on intel and nothing on
//   seattle. So was a placement voted for by the points alone over the prior's gate: 6 false
//   closures, and seattle's returns still open.
// Cost: O(n^4) hypotheses over at most `max_lines` lines per map (longest lines first), each
// verified in O(n^2); bounded by the map capacity, independent of the atlas size, and by a hard
// work bound, `max_line_checks` (verified hypotheses x lines of A x lines of B): on maps of
// many parallel walls the O(n^4) can reach tens of milliseconds. A search cut short by the
// bound cannot show that a match is unique (Condition 2), so it is refused (kRejected,
// kWorkBound), and a self-match cut short makes every match of its map refused the same way.
// The points' second look (above) is one more enumeration under the same bound, restricted to
// the prior's gate, plus at most 64 placements and the maps' repetitions scored, each by at most
// FramePointsOptions::max_scored cells (9 look-ups each), plus the shifts of the per-direction
// check (one cell apart, out to the prior's gate). All bounded by the map capacity and the point
// capacity. atlas_atlas_benchmark's BM_MatchMapsWithPoints (full frames, a loose prior, the
// laser settings) takes 2.6 ms per match; on the 25 km constant-time run the largest step was
// 6.15 ms (docs/atlas.md, session 21).

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
};

// The Condition 2 settings for maps of laser lines (atlasd with a laser, atlas-replay): `o`
// with unknown_line_correlation and alternative_sigmas 3 (why: above), redundancy_prior_halfwidth
// 1 m (default 2 m) and sigma_alpha_floor 0.02 rad (default 0.01). Over 100 seeds of the six
// corrected logs (scripts/eval-corrected-seeds.sh, docs/atlas.md session 15) the defaults' 2 m and
// 0.01 rad let 3 false closures through (chi2 beyond 3 sigma), these none:
// - csail, edge 6-2 in three seeds, 1.6-1.8 m off (d2 70-82): a 1.8 m line of one map paired
//   with a wall of the other whose parallel neighbour 1.7 m away, where the line really lies,
//   that map had not mapped there; that one pair fixed t across the walls, and a prior whose
//   gate reached 1.6-2 m either side vouched for it. An unmapped parallel wall is an
//   alternative nothing in the maps shows, and corridor walls stand 1.5-2.5 m apart, so the
//   prior vouches only when its gate is narrower than 1 m.
// - intel, edges 8-3 and 8-2 of one seed (with the 1 m half-width alone), 2 m off along a wall:
//   three short lines of a jagged wall, 0.1-0.35 rad apart, fixed t along it by their angle
//   differences, with angle variances near the 0.01 rad floor; short laser lines are off by
//   several times that (docs/atlas.md session 9: 1-3 m lines, -3.5 to +3.9 deg).
// Cost: 4 % more revisit pairs left open over the 100 seeds (intel's, mostly); mit-csail
// 0.0763 -> 0.0773 m, 0.769 deg unchanged.
MapMatchOptions LaserMapMatchOptions(MapMatchOptions o = {});

// The Condition 2 settings for maps of wide-beam sonar lines: `o` with redundancy_sigma 0.25 m
// and redundancy_prior_halfwidth 0.5 m (defaults 1 m / 2 m, laser 1 m / 1 m),
// alternative_sigmas 3, and unknown_line_correlation. Without the last, sonar edges were
// overconfident: over 200 simulated runs per cell (building and alcove loop, 16 and 24
// transducers; docs/sonar.md, session 16) the edges' chi-square against the truth averaged
// 4.0-4.4 (3 dof: 3), 12-14 % beyond the 95 % point, and 41 of 1134 edges were false closures
// (beyond 3 sigma: 0.05-1.1 m, median 0.3 m, and 0.2-5 deg off); with it 4 of 1094, the edges more
// than 0.5 m or 5 deg off 16 either way, the steps inside the robot NEES band within 1.3 points.
// A sonar atlas's priors are less consistent (robot NEES mean 6-8 on the alcove loop): with the
// laser's values of session 5 the alcove loop had gross false closures (docs/sonar.md, session 5).
// Sonar maps initialised without edge echoes (SonarInitOptions, session 11) hold few lines across a
// corridor, and a match pairing a corridor wall with the back wall of an alcove 1 m deeper was
// accepted 0.8 m off: the alternative-lines test refuses it (docs/sonar.md, session 11). Used by
// atlasd (sensors = "sonar") and by tools/sonar_eval.
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
};
inline constexpr int kMapMatchReasonCount = 9;
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
