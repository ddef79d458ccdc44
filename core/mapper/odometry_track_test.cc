#include "core/mapper/odometry_track.h"

#include <gtest/gtest.h>

#include <cmath>

namespace atlas {
namespace {

OdometrySample At(double t, double x, double y = 0, double theta = 0) {
  return OdometrySample{FromSeconds(t), Pose2{x, y, theta}};
}

TEST(OdometryTrackTest, InterpolatesBetweenBracketingSamples) {
  OdometryTrack track(8);
  track.Add(At(1.0, 0.0, 0.0, 0.0));
  track.Add(At(1.1, 1.0, 2.0, 0.2));
  track.Add(At(1.2, 3.0, 2.0, 0.2));
  Pose2 p;
  EXPECT_EQ(track.PoseAt(FromSeconds(1.05), &p), OdometryLookup::kInterpolated);
  EXPECT_NEAR(p.x, 0.5, 1e-9);
  EXPECT_NEAR(p.y, 1.0, 1e-9);
  EXPECT_NEAR(p.theta, 0.1, 1e-9);
  EXPECT_EQ(track.PoseAt(FromSeconds(1.175), &p), OdometryLookup::kInterpolated);
  EXPECT_NEAR(p.x, 2.5, 1e-9);
}

TEST(OdometryTrackTest, HeadingTakesTheShorterArc) {
  OdometryTrack track(8);
  track.Add(At(0.0, 0, 0, M_PI - 0.1));
  track.Add(At(1.0, 0, 0, -M_PI + 0.1));
  Pose2 p;
  track.PoseAt(FromSeconds(0.5), &p);
  EXPECT_NEAR(std::abs(p.theta), M_PI, 1e-9);
}

TEST(OdometryTrackTest, ExtrapolatesBrieflyThenHolds) {
  OdometryTrack track(8, std::chrono::milliseconds(100));
  track.Add(At(1.0, 0.0));
  track.Add(At(1.1, 1.0));
  Pose2 p;
  EXPECT_EQ(track.PoseAt(FromSeconds(1.15), &p), OdometryLookup::kExtrapolated);
  EXPECT_NEAR(p.x, 1.5, 1e-9);
  EXPECT_EQ(track.PoseAt(FromSeconds(2.0), &p), OdometryLookup::kHeld);
  EXPECT_NEAR(p.x, 2.0, 1e-9);  // at most 100 ms past the newest sample
}

TEST(OdometryTrackTest, BeforeTheTrackAndEmpty) {
  OdometryTrack track(8);
  Pose2 p;
  EXPECT_EQ(track.PoseAt(FromSeconds(1.0), &p), OdometryLookup::kNoData);
  track.Add(At(1.0, 4.0));
  track.Add(At(2.0, 5.0));
  EXPECT_EQ(track.PoseAt(FromSeconds(0.5), &p), OdometryLookup::kBeforeTrack);
  EXPECT_NEAR(p.x, 4.0, 1e-9);
}

TEST(OdometryTrackTest, IgnoresOutOfOrderSamplesAndWrapsAtCapacity) {
  OdometryTrack track(4);
  for (int i = 0; i < 10; ++i) track.Add(At(i, i));
  track.Add(At(5.0, 100.0));  // older than the newest: ignored
  EXPECT_EQ(track.out_of_order(), 1u);
  Pose2 p;
  EXPECT_EQ(track.PoseAt(FromSeconds(8.5), &p), OdometryLookup::kInterpolated);
  EXPECT_NEAR(p.x, 8.5, 1e-9);
  EXPECT_EQ(track.PoseAt(FromSeconds(3.0), &p), OdometryLookup::kBeforeTrack);  // overwritten
  EXPECT_NEAR(p.x, 6.0, 1e-9);
}

}  // namespace
}  // namespace atlas

namespace atlas {
namespace {

TEST(OdometryTrackTest, SeesOnlyTheSamplesKnownAtArrival) {
  OdometryTrack track(8);
  track.Add(At(1.0, 0.0));
  track.Add(At(1.1, 1.0));
  const uint64_t known = track.added();
  track.Add(At(1.2, 1.5));  // arrives after the scan: ignored for it
  Pose2 p;
  EXPECT_EQ(track.PoseAt(FromSeconds(1.15), known, &p), OdometryLookup::kExtrapolated);
  EXPECT_NEAR(p.x, 1.5, 1e-9);
  EXPECT_EQ(track.PoseAt(FromSeconds(1.15), &p), OdometryLookup::kInterpolated);
  EXPECT_NEAR(p.x, 1.25, 1e-9);
  EXPECT_EQ(track.PoseAt(FromSeconds(1.15), 0, &p), OdometryLookup::kNoData);
}

}  // namespace
}  // namespace atlas
