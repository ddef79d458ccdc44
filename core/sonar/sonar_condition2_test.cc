// Condition 2 (paper, Section II-A and IV): sonar corrects heading less than the laser, so the
// uncertainty accumulated around a loop can exceed the period of a repetitive corridor. The
// atlas's map-matching (core/atlas/map_match.h) must then refuse the ambiguous match
// (kAmbiguous) instead of accepting a wrong one, and accept it when the prior is tight.
// Hand-made sonar maps: sonar-like line covariances (sigma rho 4 cm, sigma alpha 1.1 degrees,
// as tools/sonar_eval's initialised lines), a corridor with an alcove every 4 m.

#include <gtest/gtest.h>

#include <cmath>
#include <utility>
#include <vector>

#include "core/atlas/map_match.h"
#include "core/atlas/segment_line.h"

namespace atlas {
namespace {

constexpr double kPeriod = 4.0;

// A 2.4 m corridor along x in [x0, x1] with a 1 m deep, 1.5 m wide alcove on the north side
// every kPeriod metres (frame A).
std::vector<std::pair<Vec2, Vec2>> RepetitiveCorridor(int first, int last) {
  std::vector<std::pair<Vec2, Vec2>> s;
  const double x0 = first * kPeriod, x1 = (last + 1) * kPeriod;
  s.push_back({Vec2(x0, -1.2), Vec2(x1, -1.2)});
  for (int k = first; k <= last; ++k) {
    const double a = k * kPeriod + 1.0, b = a + 1.5;
    s.push_back({Vec2(a, 1.2), Vec2(a, 2.2)});
    s.push_back({Vec2(a, 2.2), Vec2(b, 2.2)});
    s.push_back({Vec2(b, 2.2), Vec2(b, 1.2)});
  }
  return s;
}

std::vector<MapLine> SonarMap(const std::vector<std::pair<Vec2, Vec2>>& segs, const Pose2& frame) {
  const Pose2 to_frame = Inverse(frame);
  std::vector<MapLine> out;
  for (const auto& [p, q] : segs) {
    out.push_back(SegmentLine(to_frame.TransformPoint(p), to_frame.TransformPoint(q), 0.04, 0.02));
    out.back().id = static_cast<int>(out.size());
  }
  return out;
}

struct Case {
  std::vector<MapLine> a, b;
  Pose2 truth;
};

Case LoopClosure() {
  Case c;
  c.a = SonarMap(RepetitiveCorridor(0, 2), Pose2{});
  c.truth = Pose2{5.0, 0.1, 0.02};  // B's frame in A's
  c.b = SonarMap(RepetitiveCorridor(1, 3), c.truth);
  return c;
}

TEST(SonarCondition2, RepetitiveCorridorIsRepetitiveWithinEachMap) {
  const MapMatchOptions o;
  const Case c = LoopClosure();
  const SelfMatch self = SelfMatchMap(c.a, o);
  bool period_found = false;
  for (const SelfMatch::Repetition& r : self.repetitions) {
    period_found |= std::abs(std::abs(r.transform.x) - kPeriod) < 0.2 && r.support >= 3;
  }
  EXPECT_TRUE(period_found);
}

TEST(SonarCondition2, LooseSonarPriorIsRefusedAsAmbiguous) {
  const MapMatchOptions o;
  const Case c = LoopClosure();
  // Around a sonar loop the along-corridor uncertainty grows to metres (sigma 2.5 m, heading
  // 3 degrees): the prior cannot tell the true transform from one shifted by a period.
  UncertainPose prior;
  prior.mean = Compose(c.truth, Pose2{1.5, 0.0, 0.0});
  prior.cov = Vec3(2.5 * 2.5, 0.3 * 0.3, 0.05 * 0.05).asDiagonal();
  const MapMatch m = MatchMaps(c.a, SelfMatchMap(c.a, o), c.b, SelfMatchMap(c.b, o), &prior, o);
  EXPECT_EQ(m.result, MapMatchResult::kAmbiguous) << MapMatchReasonName(m.reason);
  // Without any prior every repetition matters: refused too.
  const MapMatch blind =
      MatchMaps(c.a, SelfMatchMap(c.a, o), c.b, SelfMatchMap(c.b, o), nullptr, o);
  EXPECT_NE(blind.result, MapMatchResult::kAccepted) << MapMatchReasonName(blind.reason);
}

TEST(SonarCondition2, TightPriorSatisfiesConditionTwo) {
  const MapMatchOptions o;
  const Case c = LoopClosure();
  UncertainPose prior;
  // The alcove's jambs repeat at 1.5 m and 2.5 m as well as at the 4 m period: the prior must
  // rule out a 1.5 m shift (sigma 0.25 m: 6 sigma).
  prior.mean = Compose(c.truth, Pose2{0.2, -0.05, 0.01});
  prior.cov = Vec3(0.25 * 0.25, 0.15 * 0.15, 0.03 * 0.03).asDiagonal();
  const MapMatch m = MatchMaps(c.a, SelfMatchMap(c.a, o), c.b, SelfMatchMap(c.b, o), &prior, o);
  ASSERT_EQ(m.result, MapMatchResult::kAccepted) << MapMatchReasonName(m.reason);
  EXPECT_NEAR(m.b_in_a.mean.x, c.truth.x, 0.1);
  EXPECT_NEAR(m.b_in_a.mean.y, c.truth.y, 0.1);
  EXPECT_NEAR(WrapAngle(m.b_in_a.mean.theta - c.truth.theta), 0.0, 0.02);
}

}  // namespace
}  // namespace atlas
