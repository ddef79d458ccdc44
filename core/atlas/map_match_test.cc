#include "core/atlas/map_match.h"

#include <gtest/gtest.h>

#include <Eigen/Eigenvalues>
#include <random>

#include "core/atlas/segment_line.h"

namespace atlas {
namespace {

MapLine Segment(Vec2 p, Vec2 q, double sigma_rho = 0.01, double sigma_alpha = 0.003) {
  return SegmentLine(p, q, sigma_rho, sigma_alpha);
}

// The same segments (given in A's frame) as map B sees them, B's frame being `b_in_a`.
std::vector<MapLine> SeenFrom(const std::vector<std::pair<Vec2, Vec2>>& segs, const Pose2& b_in_a,
                              double noise = 0.0, unsigned seed = 1) {
  std::mt19937 rng(seed);
  std::normal_distribution<double> n(0.0, noise);
  const Pose2 a_in_b = Inverse(b_in_a);
  std::vector<MapLine> out;
  for (const auto& [p, q] : segs) {
    Vec2 pb = a_in_b.TransformPoint(p), qb = a_in_b.TransformPoint(q);
    if (noise > 0) {
      pb += Vec2(n(rng), n(rng));
      qb += Vec2(n(rng), n(rng));
    }
    out.push_back(Segment(pb, qb));
  }
  return out;
}

std::vector<MapLine> InA(const std::vector<std::pair<Vec2, Vec2>>& segs) {
  return SeenFrom(segs, Pose2{});
}

// An irregular room: no symmetry, lines at several angles.
std::vector<std::pair<Vec2, Vec2>> Room() {
  return {{{0, 0}, {6, 0}}, {{6, 0}, {7, 3}}, {{7, 3}, {4, 5}},
          {{4, 5}, {0, 4}}, {{0, 4}, {0, 0}}, {{2, 1}, {3, 2.5}}};
}

// A comb: a corridor (walls y = 0 and y = -2.4) with identical short walls every 4 m on one
// side (repetitive structure). Two walls: a single one would fix the across direction by one
// pair alone (kSinglePair, DirectionFixedBySinglePairIsAmbiguous).
std::vector<std::pair<Vec2, Vec2>> Comb(double x0, double x1) {
  std::vector<std::pair<Vec2, Vec2>> s{{{x0, 0}, {x1, 0}}, {{x0, -2.4}, {x1, -2.4}}};
  for (double x = 0; x <= 24; x += 4)
    if (x >= x0 - 0.01 && x <= x1 + 0.01) s.push_back({{x, 0}, {x, 2}});
  return s;
}

TEST(MapMatch, RecoversTransformIndependentlyOfAnyPrior) {
  MapMatchOptions o;
  const Pose2 truth{3.0, -2.0, 0.8};
  const auto a = InA(Room());
  const auto b = SeenFrom(Room(), truth, 0.01);
  const MapMatch m = MatchMaps(a, SelfMatchMap(a, o), b, SelfMatchMap(b, o), nullptr, o);
  ASSERT_EQ(m.result, MapMatchResult::kAccepted) << MapMatchReasonName(m.reason);
  EXPECT_EQ(m.support, 6);
  EXPECT_NEAR(m.b_in_a.mean.x, truth.x, 0.05);
  EXPECT_NEAR(m.b_in_a.mean.y, truth.y, 0.05);
  EXPECT_NEAR(m.b_in_a.mean.theta, truth.theta, 0.01);
  const Eigen::SelfAdjointEigenSolver<Mat3> eig(m.b_in_a.cov);
  EXPECT_GT(eig.eigenvalues()(0), 0.0);
  // The covariance is of the order of the line covariances (cm, mrad), not a constant.
  EXPECT_LT(std::sqrt(m.b_in_a.cov(0, 0)), 0.1);
  EXPECT_LT(std::sqrt(m.b_in_a.cov(2, 2)), 0.02);
  // A wrong prior far away does not move t: it only gates (Condition 2).
  UncertainPose far{Pose2{-10, 10, 0}, Vec3(1, 1, 0.1).asDiagonal()};
  const MapMatch gated = MatchMaps(a, SelfMatchMap(a, o), b, SelfMatchMap(b, o), &far, o);
  EXPECT_EQ(gated.result, MapMatchResult::kRejected);
  EXPECT_EQ(gated.reason, MapMatchReason::kOutsidePrior);
}

TEST(MapMatch, LooserLineCovarianceGivesLooserTransform) {
  MapMatchOptions o;
  const Pose2 truth{1.0, 1.0, -0.4};
  auto a = InA(Room());
  auto b = SeenFrom(Room(), truth);
  const MapMatch tight = MatchMaps(a, {}, b, {}, nullptr, o);
  for (MapLine& l : a) l.cov *= 25;
  for (MapLine& l : b) l.cov *= 25;
  const MapMatch loose = MatchMaps(a, {}, b, {}, nullptr, o);
  ASSERT_EQ(tight.result, MapMatchResult::kAccepted);
  ASSERT_EQ(loose.result, MapMatchResult::kAccepted);
  EXPECT_GT(loose.b_in_a.cov.determinant(), tight.b_in_a.cov.determinant());
}

TEST(MapMatch, SelfMatchFindsRepetition) {
  MapMatchOptions o;
  const SelfMatch room = SelfMatchMap(InA(Room()), o);
  EXPECT_TRUE(room.repetitions.empty());
  const SelfMatch comb = SelfMatchMap(InA(Comb(0, 24)), o);
  ASSERT_FALSE(comb.repetitions.empty());
  bool shift4 = false;
  for (const auto& r : comb.repetitions)
    shift4 |= std::abs(std::abs(r.transform.x) - 4.0) < 0.1 && std::abs(r.transform.theta) < 0.01;
  EXPECT_TRUE(shift4);
}

TEST(MapMatch, AmbiguousRepetitiveStructureIsRejected) {
  MapMatchOptions o;
  const Pose2 truth{8.0, 0.5, 0.3};
  const auto a = InA(Comb(0, 24));
  const auto b = SeenFrom(Comb(7, 17), truth);
  // With self-match: the comb's teeth are not unique within either map.
  const MapMatch m = MatchMaps(a, SelfMatchMap(a, o), b, SelfMatchMap(b, o), nullptr, o);
  EXPECT_EQ(m.result, MapMatchResult::kAmbiguous);
  EXPECT_TRUE(m.reason == MapMatchReason::kRepetitive ||
              m.reason == MapMatchReason::kRivalTransform)
      << MapMatchReasonName(m.reason);
  // Without self-match the cross-match itself finds equally supported rival shifts.
  o.self_match = false;
  const MapMatch r = MatchMaps(a, {}, b, {}, nullptr, o);
  EXPECT_EQ(r.result, MapMatchResult::kAmbiguous);
  EXPECT_EQ(r.reason, MapMatchReason::kRivalTransform);
  EXPECT_GE(r.rival_support, r.support - o.min_lead + 1);
  // A loose prior (sigma 5 m) cannot tell the shifts apart either (Condition 2 violated).
  o.self_match = true;
  UncertainPose loose{Pose2{8.5, 0.0, 0.3}, Vec3(25, 25, 0.1).asDiagonal()};
  EXPECT_EQ(MatchMaps(a, SelfMatchMap(a, o), b, SelfMatchMap(b, o), &loose, o).result,
            MapMatchResult::kAmbiguous);
}

// Points every 5 cm along the segments (given in A's frame), as the frame `in` (a pose in A)
// holds them.
void AddSegmentPoints(const std::vector<std::pair<Vec2, Vec2>>& segs, const Pose2& in,
                      FramePoints* points) {
  const RigidTransform to_frame(Inverse(in));
  for (const auto& [p, q] : segs) {
    const int n = static_cast<int>((q - p).norm() / 0.05);
    for (int k = 0; k <= n; ++k) points->Add(to_frame.Apply(p + (q - p) * (double(k) / n)));
  }
}

// Condition 2 with the frames' points (map_match.h, "Points"): the comb's lines repeat every
// 4 m, but a cabinet and a desk in one bay, in both frames' scans, tell the placements apart.
// Points that repeat as the lines do cannot.
TEST(MapMatch, PointsSingleOutARepetitionOnlyWhenUnique) {
  MapMatchOptions o;
  const Pose2 truth{8.0, 0.5, 0.3};
  const auto a = InA(Comb(0, 24));
  const auto b = SeenFrom(Comb(7, 17), truth);
  const SelfMatch self_a = SelfMatchMap(a, o), self_b = SelfMatchMap(b, o);
  UncertainPose loose{Pose2{8.5, 0.0, 0.3}, Vec3(25, 25, 0.1).asDiagonal()};
  FramePointsOptions po;
  po.enabled = true;
  po.capacity = 4096;
  // B's scans saw the part of the comb from x = 7 to 12.
  FramePoints comb_a(po), comb_b(po);
  AddSegmentPoints(Comb(0, 24), Pose2{}, &comb_a);
  AddSegmentPoints(Comb(7, 12), truth, &comb_b);
  FramePoints furnished_a = comb_a, furnished_b = comb_b;
  const std::vector<std::pair<Vec2, Vec2>> furniture{
      {{9.0, 0.4}, {10.5, 0.4}},  {{9.0, 1.2}, {10.5, 1.2}},  {{9.0, 0.4}, {9.0, 1.2}},
      {{10.5, 0.4}, {10.5, 1.2}}, {{10.8, 1.0}, {11.6, 1.0}}, {{10.8, 1.6}, {11.6, 1.6}},
      {{10.8, 1.0}, {10.8, 1.6}}, {{11.6, 1.0}, {11.6, 1.6}}};
  AddSegmentPoints(furniture, Pose2{}, &furnished_a);
  AddSegmentPoints(furniture, truth, &furnished_b);

  for (const UncertainPose* prior :
       {static_cast<const UncertainPose*>(nullptr), static_cast<const UncertainPose*>(&loose)}) {
    // Lines alone, and lines with points that repeat as they do: ambiguous.
    const MapMatch lines = MatchMaps(a, self_a, b, self_b, prior, o);
    EXPECT_EQ(lines.result, MapMatchResult::kAmbiguous);
    const MapMatch periodic = MatchMaps(a, self_a, b, self_b, prior, o, &comb_a, &comb_b);
    EXPECT_EQ(periodic.result, MapMatchResult::kAmbiguous) << MapMatchReasonName(periodic.reason);
    EXPECT_FALSE(periodic.by_points);
    EXPECT_GT(periodic.point_hits, 0);
    EXPECT_GT(periodic.point_rival_hits, o.point_rival_ratio * periodic.point_hits);
    // Furnished: accepted, at the truth, with the lines' transform and covariance.
    const MapMatch m = MatchMaps(a, self_a, b, self_b, prior, o, &furnished_a, &furnished_b);
    ASSERT_EQ(m.result, MapMatchResult::kAccepted)
        << MapMatchReasonName(m.reason) << " hits " << m.point_hits << " rival "
        << m.point_rival_hits;
    EXPECT_TRUE(m.by_points);
    EXPECT_NEAR(m.b_in_a.mean.x, truth.x, 0.02);
    EXPECT_NEAR(m.b_in_a.mean.y, truth.y, 0.02);
    EXPECT_NEAR(m.b_in_a.mean.theta, truth.theta, 0.005);
    EXPECT_LE(m.point_rival_hits, o.point_rival_ratio * m.point_hits);
    EXPECT_TRUE(m.b_in_a.cov.allFinite());
    // Too few hits for the winner: refused as before.
    MapMatchOptions strict = o;
    strict.point_min_hits = m.point_hits + 1;
    EXPECT_EQ(MatchMaps(a, self_a, b, self_b, prior, strict, &furnished_a, &furnished_b).result,
              MapMatchResult::kAmbiguous);
  }
  // Points are asked only where the lines are ambiguous: a unique room is matched as before.
  const auto room_a = InA(Room());
  const auto room_b = SeenFrom(Room(), truth);
  const MapMatch room = MatchMaps(room_a, SelfMatchMap(room_a, o), room_b, SelfMatchMap(room_b, o),
                                  nullptr, o, &comb_a, &comb_b);
  EXPECT_EQ(room.result, MapMatchResult::kAccepted);
  EXPECT_FALSE(room.by_points);
  EXPECT_EQ(room.point_hits, -1);
}

TEST(MapMatch, TightPriorDisambiguatesRepetition) {
  // Condition 2 satisfied: the predicted transform is accurate to 0.3 m, the repetition is 4 m.
  MapMatchOptions o;
  const Pose2 truth{8.0, 0.5, 0.3};
  const auto a = InA(Comb(0, 24));
  const auto b = SeenFrom(Comb(7, 17), truth);
  UncertainPose prior{Pose2{8.3, 0.3, 0.32}, Vec3(0.09, 0.09, 0.01).asDiagonal()};
  const MapMatch m = MatchMaps(a, SelfMatchMap(a, o), b, SelfMatchMap(b, o), &prior, o);
  ASSERT_EQ(m.result, MapMatchResult::kAccepted) << MapMatchReasonName(m.reason);
  EXPECT_NEAR(m.b_in_a.mean.x, truth.x, 0.02);
  EXPECT_NEAR(m.b_in_a.mean.y, truth.y, 0.02);
}

// Lines of one map are correlated and MapLine has only their marginals: with
// unknown_line_correlation t's covariance is n times the independent-lines one (covariance
// intersection, equal weights).
TEST(MapMatch, CovarianceAllowsForUnknownCorrelationBetweenTheLines) {
  MapMatchOptions o;
  const Pose2 truth{1.5, -0.7, 0.4};
  const auto a = InA(Room());
  const auto b = SeenFrom(Room(), truth, 0.01);
  o.unknown_line_correlation = true;
  const MapMatch conservative = MatchMaps(a, SelfMatchMap(a, o), b, SelfMatchMap(b, o), nullptr, o);
  o.unknown_line_correlation = false;
  const MapMatch independent = MatchMaps(a, SelfMatchMap(a, o), b, SelfMatchMap(b, o), nullptr, o);
  ASSERT_EQ(conservative.result, MapMatchResult::kAccepted);
  ASSERT_EQ(independent.result, MapMatchResult::kAccepted);
  ASSERT_EQ(conservative.support, independent.support);
  EXPECT_TRUE(
      conservative.b_in_a.cov.isApprox(conservative.support * independent.b_in_a.cov, 1e-9));
  EXPECT_NEAR((conservative.b_in_a.mean.ToVector() - independent.b_in_a.mean.ToVector()).norm(),
              0.0, 1e-12);
}

// A corridor (walls y = -1.2 and y = 1.2) with a jamb at x = 6 and one at x = 10. A saw only
// the first jamb, B (2 m further along) only the second: the walls fix the across-corridor
// direction and the rotation twice over, but the along-corridor direction rests on the one jamb
// pair, and pairing B's jamb with A's gives support 3 at a transform 4 m off (the false
// closures of the sonar alcove loop: atlas-sonar-eval atlas --world alcoves). That match is
// ambiguous; with both jambs in both maps it is accepted.
TEST(MapMatch, DirectionFixedBySinglePairIsAmbiguous) {
  MapMatchOptions o;
  const Pose2 truth{2.0, 0.0, 0.0};
  const std::pair<Vec2, Vec2> south{{0, -1.2}, {14, -1.2}}, north{{0, 1.2}, {14, 1.2}},
      jamb6{{6, 1.2}, {6, 2.2}}, jamb10{{10, 1.2}, {10, 2.2}};
  const auto a = InA({south, north, jamb6});
  const auto b = SeenFrom({south, north, jamb10}, truth);
  const MapMatch m = MatchMaps(a, SelfMatchMap(a, o), b, SelfMatchMap(b, o), nullptr, o);
  EXPECT_EQ(m.result, MapMatchResult::kAmbiguous);
  EXPECT_EQ(m.reason, MapMatchReason::kSinglePair) << MapMatchReasonName(m.reason);
  // Without the test, the wrong pairing is accepted: t is 4 m off along the corridor with a
  // covariance of centimetres.
  o.redundancy_sigma = 0.0;
  const MapMatch unguarded = MatchMaps(a, SelfMatchMap(a, o), b, SelfMatchMap(b, o), nullptr, o);
  ASSERT_EQ(unguarded.result, MapMatchResult::kAccepted);
  EXPECT_NEAR(unguarded.b_in_a.mean.x, truth.x - 4.0, 0.05);
  EXPECT_LT(std::sqrt(unguarded.b_in_a.cov(0, 0)), 0.1);
  // A prior whose gate along the corridor is within redundancy_prior_halfwidth (sigma 0.1 m:
  // +-0.4 m) vouches for the one jamb pair, right or wrong (here it is the wrong one: a tight
  // prior is believed, Condition 2); with the half width 0 nothing does.
  o = MapMatchOptions{};
  o.redundancy_prior_halfwidth = 0.5;
  const UncertainPose tight{Pose2{-2.05, 0.0, 0.0}, Vec3(0.01, 0.01, 0.001).asDiagonal()};
  const MapMatch vouched = MatchMaps(a, SelfMatchMap(a, o), b, SelfMatchMap(b, o), &tight, o);
  EXPECT_EQ(vouched.result, MapMatchResult::kAccepted) << MapMatchReasonName(vouched.reason);
  o.redundancy_prior_halfwidth = 0.0;
  EXPECT_EQ(MatchMaps(a, SelfMatchMap(a, o), b, SelfMatchMap(b, o), &tight, o).reason,
            MapMatchReason::kSinglePair);
  // Both jambs in both maps and a prior (0.3 m) that tells the 4 m self-repetition (walls and
  // one jamb) from t: every direction has two pairs, the match is accepted and true.
  o = MapMatchOptions{};
  const auto a2 = InA({south, north, jamb6, jamb10});
  const auto b2 = SeenFrom({south, north, jamb6, jamb10}, truth);
  const UncertainPose prior{Pose2{2.2, 0.1, 0.01}, Vec3(0.09, 0.09, 0.01).asDiagonal()};
  const MapMatch both = MatchMaps(a2, SelfMatchMap(a2, o), b2, SelfMatchMap(b2, o), &prior, o);
  ASSERT_EQ(both.result, MapMatchResult::kAccepted) << MapMatchReasonName(both.reason);
  EXPECT_NEAR(both.b_in_a.mean.x, truth.x, 0.05);
  EXPECT_NEAR(both.b_in_a.mean.y, truth.y, 0.05);
}

// The points fix a direction that one pair alone fixes only by a search out to the prior's
// gate, one placement per cell of shift: a gate beyond point_max_shift leaves it unfixed, so
// that a loose prior cannot make the search long. A corridor with a jamb every 4 m (A) of
// which B saw one: the lines place B at every jamb inside the gate, the legs of a bench that
// both scans saw single out the true one, and the along-corridor direction rests on the one
// jamb pair, so the points must fix it too.
TEST(MapMatch, PointsFixADirectionOnlyWithinTheirSearchBound) {
  MapMatchOptions o;
  const Pose2 truth{2.0, 0.0, 0.0};
  const std::pair<Vec2, Vec2> south{{-10, -1.2}, {24, -1.2}}, north{{-10, 1.2}, {24, 1.2}};
  auto jamb = [](double x) { return std::pair<Vec2, Vec2>{{x, 1.2}, {x, 2.2}}; };
  const auto a = InA({south, north, jamb(-2), jamb(2), jamb(6), jamb(10), jamb(14)});
  const auto b = SeenFrom({south, north, jamb(6)}, truth);
  FramePointsOptions po;
  po.enabled = true;
  FramePoints pa(po), pb(po);
  // What the scans saw: the walls and the jamb near x = 6, and the legs of a bench, across
  // the corridor at uneven spacing.
  std::vector<std::pair<Vec2, Vec2>> seen{{{5, -1.2}, {7, -1.2}}, {{5, 1.2}, {7, 1.2}}, jamb(6)};
  for (double x : {4.3, 4.75, 5.6, 6.45, 7.05, 7.9}) seen.push_back({{x, -1.1}, {x, -0.5}});
  AddSegmentPoints(seen, Pose2{}, &pa);
  AddSegmentPoints(seen, truth, &pb);
  const SelfMatch self_a = SelfMatchMap(a, o), self_b = SelfMatchMap(b, o);
  // Sigma 1 m along the corridor: the gate (+-4 m) holds three jambs and is wider than the
  // prior may vouch for (redundancy_prior_halfwidth 2 m); the points choose and fix it.
  const UncertainPose near{Pose2{2.3, 0.0, 0.0}, Vec3(1.0, 0.04, 0.001).asDiagonal()};
  EXPECT_EQ(MatchMaps(a, self_a, b, self_b, &near, o).result, MapMatchResult::kAmbiguous);
  const MapMatch fixed = MatchMaps(a, self_a, b, self_b, &near, o, &pa, &pb);
  ASSERT_EQ(fixed.result, MapMatchResult::kAccepted) << MapMatchReasonName(fixed.reason);
  EXPECT_TRUE(fixed.by_points);
  EXPECT_NEAR(fixed.b_in_a.mean.x, truth.x, 0.05);
  // Sigma 3 m: the gate reaches 12 m, beyond point_max_shift (10 m): not searched, not fixed.
  const UncertainPose loose{Pose2{2.3, 0.0, 0.0}, Vec3(9.0, 0.04, 0.001).asDiagonal()};
  // (The refusal keeps the lines' reason; the points found their placement all the same.)
  const MapMatch unsearched = MatchMaps(a, self_a, b, self_b, &loose, o, &pa, &pb);
  EXPECT_EQ(unsearched.result, MapMatchResult::kAmbiguous);
  EXPECT_FALSE(unsearched.by_points);
  EXPECT_GE(unsearched.point_hits, o.point_min_hits);
  EXPECT_EQ(unsearched.point_rival_hits, 0);
  o.point_max_shift = 20.0;
  const MapMatch searched = MatchMaps(a, self_a, b, self_b, &loose, o, &pa, &pb);
  EXPECT_EQ(searched.result, MapMatchResult::kAccepted) << MapMatchReasonName(searched.reason);
}

// A csail edge (docs/design.md, "Redundancy: one direction, one pair"): the pair that alone fixes
// one direction of t has an alternative 1.7 m away that the maps do not show. Here a corridor with
// one jamb: A mapped the jamb at x = 6, B (seen from x = 2) only another at x = 7.7 (world), so
// pairing the two jambs puts t 1.7 m off along the corridor. A prior of sigma 0.4 m (gate +-1.6 m)
// holds both placements. With the default 2 m half-width the prior vouches for the one pair and the
// wrong t is accepted; with the laser's 1 m it does not: kSinglePair.
TEST(MapMatch, PriorVouchesForASinglePairOnlyWithinTheLaserHalfWidth) {
  const Pose2 truth{2.0, 0.0, 0.0};
  const std::pair<Vec2, Vec2> south{{0, -1.2}, {14, -1.2}}, north{{0, 1.2}, {14, 1.2}};
  const auto a = InA({south, north, {{6, 1.2}, {6, 2.2}}});
  const auto b = SeenFrom({south, north, {{7.7, 1.2}, {7.7, 2.2}}}, truth);
  const UncertainPose prior{Pose2{1.15, 0.0, 0.0}, Vec3(0.16, 0.01, 0.001).asDiagonal()};
  MapMatchOptions o;
  const MapMatch vouched = MatchMaps(a, SelfMatchMap(a, o), b, SelfMatchMap(b, o), &prior, o);
  ASSERT_EQ(vouched.result, MapMatchResult::kAccepted) << MapMatchReasonName(vouched.reason);
  EXPECT_NEAR(vouched.b_in_a.mean.x, truth.x - 1.7, 0.05);
  o = LaserMapMatchOptions();
  const MapMatch refused = MatchMaps(a, SelfMatchMap(a, o), b, SelfMatchMap(b, o), &prior, o);
  EXPECT_EQ(refused.result, MapMatchResult::kAmbiguous);
  EXPECT_EQ(refused.reason, MapMatchReason::kSinglePair) << MapMatchReasonName(refused.reason);
  // A prior of sigma 0.2 m (gate +-0.8 m) still vouches: it tells placements 1.7 m apart.
  const UncertainPose tight{Pose2{0.3, 0.0, 0.0}, Vec3(0.04, 0.01, 0.001).asDiagonal()};
  EXPECT_EQ(MatchMaps(a, SelfMatchMap(a, o), b, SelfMatchMap(b, o), &tight, o).result,
            MapMatchResult::kAccepted);
}

// A wall with a 0.4 m step (freiburg-079; docs/design.md, "Alternative lines"): the recessed face
// x = -0.4 (y 1 .. -1.6) and the forward face x = 0 (y -1.6 .. -6.4), and three cross walls
// whose normals lie within 0.13 rad of the y axis, so they fix y and the rotation well and x
// only loosely. A saw the forward face whole and a metre of the recessed one (its line 0.09 rad
// off, as short lines are); B saw the recessed face and the cross walls. Pairing B's recessed
// face with A's forward face gives support 4 at t 0.4 m off in x, and that one pair makes t's x
// sigma a tenth of that; the cross walls alone leave x to about 0.3 m, "redundant" by the 1 m
// test. A's short recessed line is the alternative the maps show: the placement that puts B's
// face on it is 0.4 m away, inside the prior and every other pair's gate: kAmbiguous
// (kSinglePair). With a wall that fixes x twice over, or a prior that excludes the alternative,
// B seeing the forward face is accepted and true.
TEST(MapMatch, PairWithAnAlternativeLineNothingElseExcludesIsAmbiguous) {
  MapMatchOptions o;
  o.unknown_line_correlation = true;
  const Pose2 truth{-9.7, 3.4, -0.23};
  const std::pair<Vec2, Vec2> forward{{0, -1.6}, {0, -6.4}}, recessed{{-0.4, 1.0}, {-0.4, -1.6}},
      recessed_piece{{-0.445, -0.5}, {-0.355, -1.5}}, cross1{{1.5, 0.5}, {3.0, 0.3}},
      cross2{{-1.0, 0.5}, {1.0, 0.5}}, cross3{{-1.0, -7.4}, {2.0, -7.0}};
  const auto a = InA({forward, recessed_piece, cross1, cross2, cross3});
  const auto b = SeenFrom({recessed, cross1, cross2, cross3}, truth);
  // Without the test the wrong pairing is accepted, 0.4 m off in x, beyond 3 sigma of its own
  // covariance.
  const MapMatch unguarded = MatchMaps(a, SelfMatchMap(a, o), b, SelfMatchMap(b, o), nullptr, o);
  ASSERT_EQ(unguarded.result, MapMatchResult::kAccepted) << MapMatchReasonName(unguarded.reason);
  EXPECT_EQ(unguarded.support, 4);
  const double error_x = unguarded.b_in_a.mean.x - truth.x;
  EXPECT_GT(error_x, 0.3);
  EXPECT_GT(error_x, 3.0 * std::sqrt(unguarded.b_in_a.cov(0, 0)));
  o.alternative_sigmas = 3.0;
  const MapMatch m = MatchMaps(a, SelfMatchMap(a, o), b, SelfMatchMap(b, o), nullptr, o);
  EXPECT_EQ(m.result, MapMatchResult::kAmbiguous);
  EXPECT_EQ(m.reason, MapMatchReason::kSinglePair) << MapMatchReasonName(m.reason);
  // A prior that holds both placements (sigma 0.13 m in x, as edge 8-0's) does not help.
  const UncertainPose loose{Pose2{-9.5, 3.45, -0.19}, Vec3(0.018, 0.068, 0.0008).asDiagonal()};
  EXPECT_EQ(MatchMaps(a, SelfMatchMap(a, o), b, SelfMatchMap(b, o), &loose, o).reason,
            MapMatchReason::kSinglePair);
  // B sees the forward face (the true pairing): with nothing else fixing x, the recessed piece
  // is as good an alternative; a prior that excludes it (sigma 0.05 m) or a diagonal wall both
  // maps saw (it fixes x with the cross walls) settles it, and the match is accepted and true.
  const auto b_forward = SeenFrom({forward, cross1, cross2, cross3}, truth);
  EXPECT_EQ(
      MatchMaps(a, SelfMatchMap(a, o), b_forward, SelfMatchMap(b_forward, o), nullptr, o).reason,
      MapMatchReason::kSinglePair);
  const UncertainPose tight{Pose2{-9.72, 3.41, -0.232}, Vec3(0.0025, 0.0025, 0.0004).asDiagonal()};
  const MapMatch with_prior =
      MatchMaps(a, SelfMatchMap(a, o), b_forward, SelfMatchMap(b_forward, o), &tight, o);
  ASSERT_EQ(with_prior.result, MapMatchResult::kAccepted) << MapMatchReasonName(with_prior.reason);
  EXPECT_NEAR(with_prior.b_in_a.mean.x, truth.x, 0.05);
  const std::pair<Vec2, Vec2> diagonal{{3, -2}, {5, -4}};
  const auto a2 = InA({forward, recessed_piece, cross1, cross2, cross3, diagonal});
  const auto b2 = SeenFrom({forward, cross1, cross2, cross3, diagonal}, truth);
  const MapMatch both = MatchMaps(a2, SelfMatchMap(a2, o), b2, SelfMatchMap(b2, o), nullptr, o);
  ASSERT_EQ(both.result, MapMatchResult::kAccepted) << MapMatchReasonName(both.reason);
  EXPECT_NEAR(both.b_in_a.mean.x, truth.x, 0.05);
  EXPECT_NEAR(both.b_in_a.mean.y, truth.y, 0.05);
}

TEST(MapMatch, ParallelOrTooFewLinesAreRejected) {
  MapMatchOptions o;
  const std::vector<std::pair<Vec2, Vec2>> corridor{
      {{0, 0}, {10, 0}}, {{0, 2}, {10, 2}}, {{12, 0}, {20, 0}}, {{12, 2}, {20, 2}}};
  const auto a = InA(corridor);
  const auto b = SeenFrom(corridor, Pose2{1, 0, 0});
  const MapMatch m = MatchMaps(a, {}, b, {}, nullptr, o);
  EXPECT_EQ(m.result, MapMatchResult::kRejected);
  const auto two = InA({{{0, 0}, {5, 0}}, {{0, 0}, {0, 5}}});
  EXPECT_EQ(MatchMaps(two, {}, two, {}, nullptr, o).reason, MapMatchReason::kTooFewLines);
  // Garbage lines (NaN) are ignored, not trusted.
  auto bad = InA(Room());
  for (MapLine& l : bad) l.rho = std::nan("");
  EXPECT_EQ(MatchMaps(bad, {}, bad, {}, nullptr, o).result, MapMatchResult::kRejected);
  EXPECT_EQ(o.Validate(), "");
}

}  // namespace
}  // namespace atlas

namespace atlas {
namespace {

// The work bound: a search cut short is refused, never judged on what it happened to find.
TEST(MapMatch, SearchCutShortByTheWorkBoundIsRefused) {
  MapMatchOptions o;
  const Pose2 truth{8.0, 0.5, 0.3};
  const auto a = InA(Comb(0, 24));
  const auto b = SeenFrom(Comb(7, 17), truth);
  UncertainPose prior{Pose2{8.3, 0.3, 0.32}, Vec3(0.09, 0.09, 0.01).asDiagonal()};
  const SelfMatch self_a = SelfMatchMap(a, o), self_b = SelfMatchMap(b, o);
  ASSERT_TRUE(self_a.complete && self_b.complete);
  ASSERT_EQ(MatchMaps(a, self_a, b, self_b, &prior, o).result, MapMatchResult::kAccepted);

  // A bound too small for the cross-match (self-matches complete): refused.
  MapMatchOptions tight = o;
  tight.max_line_checks = 50 * static_cast<int64_t>(a.size()) * static_cast<int64_t>(b.size());
  const MapMatch m = MatchMaps(a, self_a, b, self_b, &prior, tight);
  EXPECT_EQ(m.result, MapMatchResult::kRejected);
  EXPECT_EQ(m.reason, MapMatchReason::kWorkBound);
  EXPECT_LE(m.hypotheses, 50);

  // A self-match cut short: its repetitions are unknown, so every match of that map is refused.
  tight.max_line_checks = 10;
  const SelfMatch partial = SelfMatchMap(a, tight);
  EXPECT_FALSE(partial.complete);
  const MapMatch r = MatchMaps(a, partial, b, self_b, &prior, o);
  EXPECT_EQ(r.result, MapMatchResult::kRejected);
  EXPECT_EQ(r.reason, MapMatchReason::kWorkBound);
  EXPECT_EQ(r.hypotheses, 0);
}

}  // namespace
}  // namespace atlas
