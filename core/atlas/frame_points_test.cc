#include "core/atlas/frame_points.h"

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <random>

namespace atlas {
namespace {

FramePointsOptions SmallCells() {
  FramePointsOptions o;
  o.enabled = true;
  o.cell = 0.1;
  o.capacity = 64;
  return o;
}

TEST(FramePoints, OptionsAreValidated) {
  EXPECT_EQ(FramePointsOptions{}.Validate(), "");
  FramePointsOptions o;
  o.cell = 0.0;
  EXPECT_NE(o.Validate(), "");
  o = {};
  o.capacity = 8;
  EXPECT_NE(o.Validate(), "");
  o = {};
  o.max_range = -1.0;
  EXPECT_NE(o.Validate(), "");
  o = {};
  o.max_scored = 0;
  EXPECT_NE(o.Validate(), "");
}

TEST(FramePoints, StoresEachCellOnceUpToItsCapacity) {
  FramePoints p(SmallCells());
  EXPECT_TRUE(p.Add(Vec2(0.01, 0.01)));
  EXPECT_TRUE(p.Add(Vec2(0.09, 0.05)));  // the same cell
  EXPECT_EQ(p.Size(), 1);
  EXPECT_TRUE(p.Contains(Vec2(0.05, 0.05)));
  EXPECT_FALSE(p.Contains(Vec2(0.15, 0.05)));
  EXPECT_TRUE(p.Add(Vec2(-0.01, -0.01)));  // cell (-1, -1), next to the origin's
  EXPECT_EQ(p.Size(), 2);
  for (int k = 0; k < 100; ++k) p.Add(Vec2(0.1 * k + 0.05, 1.05));
  EXPECT_EQ(p.Size(), 64);
  EXPECT_FALSE(p.Add(Vec2(-5.0, -5.0)));  // a new cell beyond the capacity
  EXPECT_TRUE(p.Add(Vec2(0.05, 1.05)));   // a cell it has
  EXPECT_EQ(p.Size(), 64);
  // Points beyond the cell index range are not stored.
  EXPECT_FALSE(p.Add(Vec2(1e6, 0.0)));
  EXPECT_FALSE(p.Contains(Vec2(1e6, 0.0)));
}

TEST(FramePoints, AddsScanEndpointsInTheFrame) {
  FramePointsOptions o = SmallCells();
  o.capacity = 1024;
  o.max_range = 5.0;
  FramePoints p(o);
  LaserScan scan;
  scan.angle_min = static_cast<float>(-std::numbers::pi / 2);
  scan.angle_increment = static_cast<float>(std::numbers::pi / 2);
  scan.max_range = 30.0f;
  scan.ranges = {1.0f, 2.0f, 6.0f};  // right 1 m, ahead 2 m, left 6 m (beyond max_range)
  scan.sensor_pose = Pose2{0.5, 0.0, 0.0};
  // The robot at (10.03, 0.04), facing +y: the sensor at (10.03, 0.54), its right is +x.
  // (Positions inside cells, not on their borders.)
  p.AddScan(Pose2{10.03, 0.04, std::numbers::pi / 2}, scan);
  EXPECT_EQ(p.Size(), 2);
  EXPECT_TRUE(p.Contains(Vec2(11.03, 0.54)));
  EXPECT_TRUE(p.Contains(Vec2(10.03, 2.54)));
  EXPECT_FALSE(p.Contains(Vec2(4.03, 0.54)));
  scan.ranges = {kNoReturn, 0.0f, 1.0f};
  p.AddScan(Pose2{0.03, 0.04, 0.0}, scan);
  EXPECT_EQ(p.Size(), 3);  // only the left return, at (0.53, 1.04)
  EXPECT_TRUE(p.Contains(Vec2(0.53, 1.04)));
}

// An L of points (a wall and a door jamb): only the right placement of a copy scores fully.
TEST(FramePoints, ScoresPlacementsOfAnotherFrame) {
  FramePointsOptions o = SmallCells();
  o.capacity = 1024;
  FramePoints a(o), b(o);
  for (int k = 0; k < 100; ++k) a.Add(Vec2(0.1 * k + 0.05, 0.05));
  for (int k = 1; k < 10; ++k) a.Add(Vec2(5.05, 0.1 * k + 0.05));
  // B: the same structure seen from a frame at (2, 0) turned by a quarter turn.
  const Pose2 b_in_a{2.0, 0.0, std::numbers::pi / 2};
  for (const Vec2& c : a.Centres()) b.Add(RigidTransform(Inverse(b_in_a)).Apply(c));
  ASSERT_EQ(b.Size(), a.Size());
  const FramePoints::Score right = a.ScoreOf(b, b_in_a);
  EXPECT_EQ(right.scored, b.Size());
  EXPECT_EQ(right.hits, b.Size());
  // Shifted along the wall by 2 m: the wall still scores, the jamb does not.
  const FramePoints::Score along = a.ScoreOf(b, Pose2{4.0, 0.0, std::numbers::pi / 2});
  EXPECT_LT(along.hits, right.hits);
  EXPECT_GE(along.hits, 70);
  // Beside it by 1.5 m: nothing.
  EXPECT_EQ(a.ScoreOf(b, Pose2{2.0, -1.5, std::numbers::pi / 2}).hits, 0);
  // Scoring is bounded by max_scored, strided evenly.
  FramePointsOptions bounded = o;
  bounded.max_scored = 20;
  FramePoints a_bounded(bounded);
  for (const Vec2& c : a.Centres()) a_bounded.Add(c);
  const FramePoints::Score few = a_bounded.ScoreOf(b, b_in_a);
  EXPECT_LE(few.scored, 20);
  EXPECT_GE(few.scored, 10);
  EXPECT_EQ(few.hits, few.scored);
  // An empty set scores nothing either way.
  const FramePoints empty(o);
  EXPECT_EQ(a.ScoreOf(empty, b_in_a).scored, 0);
  EXPECT_EQ(empty.ScoreOf(b, b_in_a).hits, 0);
}

// HitsNear is ScoreOf's hit count, placement for placement: random walls of points (some far
// apart, some on the index range's edge), random placements near and far.
TEST(FramePoints, HitsNearCountAsScoreOf) {
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  for (int trial = 0; trial < 20; ++trial) {
    FramePointsOptions o;
    o.max_scored = trial % 2 == 0 ? 512 : 64;
    FramePoints a(o), b(o);
    const double spread = trial % 5 == 0 ? 3000.0 : 15.0;
    for (int wall = 0; wall < 6; ++wall) {
      const Vec2 start(spread * u(rng), spread * u(rng));
      const Vec2 dir(std::cos(3.0 * u(rng)), std::sin(3.0 * u(rng)));
      for (int k = 0; k < 120; ++k) {
        a.Add(start + 0.05 * k * dir);
        b.Add(start + 0.05 * k * dir + Vec2(0.02 * u(rng), 0.02 * u(rng)));
      }
    }
    if (trial == 3) a.Add(Vec2(3276.0, -3276.0));  // near the index range's end
    const FramePoints::NearCells near = a.Near();
    EXPECT_EQ(near.empty(), trial % 5 == 0 || trial == 3) << trial;  // too large: ScoreOf
    for (int k = 0; k < 50; ++k) {
      const double far = k % 10 == 0 ? 5000.0 : 0.5;
      const Pose2 t{far * u(rng), far * u(rng), 0.2 * u(rng)};
      EXPECT_EQ(a.HitsNear(near, b, t), a.ScoreOf(b, t).hits) << trial << " " << k;
    }
    EXPECT_GT(a.HitsNear(near, b, Pose2{}), 0);
  }
  EXPECT_TRUE(FramePoints().Near().empty());
}

TEST(FramePoints, ImageRoundTripsAndRejectsGarbage) {
  FramePoints p(SmallCells());
  for (int k = 0; k < 30; ++k) p.Add(Vec2(0.3 * k - 4.0, 0.2 * k - 3.0));
  const std::string image = p.Serialize();
  FramePoints q(SmallCells());
  ASSERT_TRUE(q.Deserialize(image));
  EXPECT_EQ(q.Size(), p.Size());
  EXPECT_TRUE(q.Serialize() == image);
  for (const Vec2& c : p.Centres()) EXPECT_TRUE(q.Contains(c));
  FramePoints r(SmallCells());
  r.Add(Vec2(9.0, 9.0));
  EXPECT_FALSE(r.Deserialize(image.substr(0, image.size() - 1)));
  EXPECT_FALSE(r.Deserialize(image + "x"));
  std::string zero_key = image;
  zero_key.replace(4, 4, std::string(4, '\0'));  // not a key Add() can make
  EXPECT_FALSE(r.Deserialize(zero_key));
  EXPECT_EQ(r.Size(), 1);
  // An image of more cells than the capacity keeps the first ones.
  FramePointsOptions small = SmallCells();
  small.capacity = 16;
  FramePoints s(small);
  ASSERT_TRUE(s.Deserialize(image));
  EXPECT_EQ(s.Size(), 16);
}

}  // namespace
}  // namespace atlas
