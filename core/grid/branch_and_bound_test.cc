#include "core/grid/branch_and_bound.h"

#include <gtest/gtest.h>

#include <random>

#include "core/testing/grid_scenes.h"

namespace atlas {
namespace {

// A 3 x 3 m grid with a few random occupied blobs, and points drawn from them seen from a
// random pose.
struct RandomCase {
  ProbabilityGrid grid{ProbabilityGridOptions{}};
  std::vector<Vec2> points;
  Pose2 center;
};

RandomCase MakeRandomCase(uint64_t seed) {
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  ProbabilityGridOptions o;
  o.resolution = 0.1;
  RandomCase c{ProbabilityGrid(o, Vec2(-1.5, -1.5), Vec2(1.49, 1.49)), {}, {}};
  std::vector<uint16_t>& values = c.grid.mutable_values();
  for (uint16_t& v : values) {
    const double r = u(rng);
    v = r < 0.5 ? ProbabilityGrid::kUnknown : c.grid.ValueOfProbability(r < 0.85 ? 0.2 : u(rng));
  }
  const Pose2 truth{u(rng) - 0.5, u(rng) - 0.5, u(rng) - 0.5};
  const RigidTransform to_points(Inverse(truth));
  for (int i = 0; i < 25; ++i) {
    c.points.push_back(to_points.Apply(Vec2(2.4 * u(rng) - 1.2, 2.4 * u(rng) - 1.2)));
  }
  c.center = Pose2{truth.x + 0.3 * (u(rng) - 0.5), truth.y + 0.3 * (u(rng) - 0.5),
                   truth.theta + 0.2 * (u(rng) - 0.5)};
  return c;
}

BranchAndBoundOptions SmallWindow(int depth) {
  BranchAndBoundOptions o;
  o.depth = depth;
  o.linear_window = 0.5;
  o.angular_window = 0.15;
  o.peak_distance = 0.2;
  o.peak_angle = 0.05;
  return o;
}

// The level-0 score of `p`, summed here rather than by the search.
int64_t LevelZeroSum(const PrecomputationGridStack& grids, const std::vector<Vec2>& points,
                     const Pose2& center, const SearchWindow& window, const Placement& p) {
  DiscreteScans scans;
  DiscretizeScans(grids.limits(), points, center, window, &scans);
  int64_t sum = 0;
  for (int i = 0; i < scans.points; ++i) {
    const CellIndex c = scans.Heading(p.heading)[i];
    sum += grids.Level(0).At(CellIndex{c.x + p.x, c.y + p.y});
  }
  return sum;
}

BranchAndBoundResult SearchAtOnce(const PrecomputationGridStack& grids,
                                  const std::vector<Vec2>& points, const Pose2& center,
                                  const BranchAndBoundOptions& options) {
  BranchAndBoundSearch search(grids, points, center, options);
  EXPECT_EQ(search.Run(std::numeric_limits<int64_t>::max()), SearchStatus::kDone);
  return search.result();
}

TEST(BranchAndBound, EqualsExhaustiveSearchOnRandomCases) {
  for (uint64_t seed = 1; seed <= 40; ++seed) {
    const RandomCase c = MakeRandomCase(seed);
    const int depth = 1 + static_cast<int>(seed % 5);
    const BranchAndBoundOptions o = SmallWindow(depth);
    const PrecomputationGridStack grids(c.grid, depth);
    BranchAndBoundSearch search(grids, c.points, c.center, o);
    ASSERT_EQ(search.Run(std::numeric_limits<int64_t>::max()), SearchStatus::kDone);
    const BranchAndBoundResult& b = search.result();
    const BranchAndBoundResult e = ExhaustiveSearch(grids, c.points, c.center, o);
    ASSERT_TRUE(e.best.found);
    ASSERT_TRUE(b.best.found) << seed;
    EXPECT_EQ(b.best.sum, e.best.sum) << seed;
    EXPECT_EQ(LevelZeroSum(grids, c.points, c.center, search.window(), b.best.placement),
              b.best.sum)
        << seed;
    EXPECT_DOUBLE_EQ(b.best.score, e.best.score);
    // The runner-up is outside the peak of the best placement; when the best is unique the two
    // searches share the peak and so the runner-up's score.
    ASSERT_TRUE(b.runner_up.found);
    const Peak peak =
        MakePeak(b.best.placement, o.peak_distance, o.peak_angle, 0.1, search.window());
    EXPECT_FALSE(peak.Contains(b.runner_up.placement));
    if (b.best.placement.heading == e.best.placement.heading &&
        b.best.placement.x == e.best.placement.x && b.best.placement.y == e.best.placement.y) {
      EXPECT_EQ(b.runner_up.sum, e.runner_up.sum) << seed;
      EXPECT_DOUBLE_EQ(b.margin, e.margin);
    } else {
      EXPECT_EQ(b.runner_up.sum, b.best.sum) << seed;  // a tie: another peak as good
    }
  }
}

TEST(BranchAndBound, SlicedSearchEqualsOneShot) {
  for (uint64_t seed = 100; seed < 110; ++seed) {
    const RandomCase c = MakeRandomCase(seed);
    const BranchAndBoundOptions o = SmallWindow(4);
    const PrecomputationGridStack grids(c.grid, o.depth);
    BranchAndBoundSearch one_shot(grids, c.points, c.center, o);
    ASSERT_EQ(one_shot.Run(std::numeric_limits<int64_t>::max()), SearchStatus::kDone);
    for (int64_t slice : {1, 7, 100}) {
      BranchAndBoundSearch sliced(grids, c.points, c.center, o);
      int calls = 0;
      int64_t last_nodes = 0;
      while (sliced.Run(slice) == SearchStatus::kRunning) {
        ++calls;
        ASSERT_LE(sliced.result().nodes - last_nodes, slice);
        last_nodes = sliced.result().nodes;
      }
      EXPECT_TRUE(sliced.done());
      EXPECT_GT(calls, 0);
      const BranchAndBoundResult& a = one_shot.result();
      const BranchAndBoundResult& b = sliced.result();
      EXPECT_EQ(b.nodes, a.nodes);
      EXPECT_EQ(b.best.sum, a.best.sum);
      EXPECT_EQ(b.best.placement.heading, a.best.placement.heading);
      EXPECT_EQ(b.best.placement.x, a.best.placement.x);
      EXPECT_EQ(b.best.placement.y, a.best.placement.y);
      EXPECT_EQ(b.runner_up.sum, a.runner_up.sum);
      EXPECT_EQ(b.margin, a.margin);
    }
  }
}

// The runner-up pass as a decision (rival_margin) answers as the full pass for every margin:
// a rival within the margin exists exactly when the full pass's margin is below it.
TEST(BranchAndBound, RivalDecisionAnswersAsTheFullRunnerUpPass) {
  int64_t full_nodes = 0, decision_nodes = 0;
  int rivals = 0, unique = 0;
  for (uint64_t seed = 1; seed <= 40; ++seed) {
    const RandomCase c = MakeRandomCase(seed);
    BranchAndBoundOptions o = SmallWindow(1 + static_cast<int>(seed % 5));
    const PrecomputationGridStack grids(c.grid, o.depth);
    const BranchAndBoundResult full = SearchAtOnce(grids, c.points, c.center, o);
    ASSERT_TRUE(full.best.found);
    for (double margin : {0.01, 0.05, 0.1, 0.2}) {
      o.rival_margin = margin;
      const BranchAndBoundResult d = SearchAtOnce(grids, c.points, c.center, o);
      EXPECT_EQ(d.best.sum, full.best.sum) << seed;
      EXPECT_EQ(d.margin < margin, full.margin < margin) << seed << " " << margin;
      if (full.margin < margin) {
        ++rivals;
        ASSERT_TRUE(d.runner_up.found);
        EXPECT_LE(d.runner_up.sum, full.runner_up.sum);  // a rival, not necessarily the best
      } else {
        ++unique;
        EXPECT_FALSE(d.runner_up.found);
      }
      EXPECT_LE(d.nodes, full.nodes);
      full_nodes += full.nodes;
      decision_nodes += d.nodes;
    }
  }
  EXPECT_GT(rivals, 10);  // both answers are exercised
  EXPECT_GT(unique, 10);
  EXPECT_LT(decision_nodes, full_nodes);
}

TEST(BranchAndBound, FindsAScanInARoomOverAWideWindowWithAClearMargin) {
  const GridOptions o;
  const std::vector<sim::Wall> walls = RoomWalls();
  const ProbabilityGrid grid = ScannedGrid(walls, RoomTour(), o);
  const PrecomputationGridStack grids(grid, o.search.depth);
  const Pose2 truth{1.0, 1.5, 0.7};
  const std::vector<Vec2> points = ScanPoints(walls, truth, o);
  BranchAndBoundSearch search(grids, points, Pose2{2.3, 0.4, 0.95}, o.search);
  search.Run(std::numeric_limits<int64_t>::max());
  const BranchAndBoundResult& r = search.result();
  ASSERT_TRUE(r.best.found);
  EXPECT_NEAR(r.best.pose.x, truth.x, 0.05);
  EXPECT_NEAR(r.best.pose.y, truth.y, 0.05);
  EXPECT_NEAR(r.best.pose.theta, truth.theta, search.window().angular_step);
  EXPECT_GT(r.margin, 0.1);
  // The window holds 81^2 translations at each of about 2 x 0.35 / 0.0017 headings.
  const int64_t placements = int64_t{81} * 81 * search.window().headings();
  EXPECT_LT(r.nodes * 50, placements);
  std::cout << "room: score " << r.best.score << " runner-up " << r.runner_up.score << " nodes "
            << r.nodes << " of " << placements << " placements\n";
}

TEST(BranchAndBound, ARepetitivePlaceHasASmallMargin) {
  const GridOptions o;
  const std::vector<sim::Wall> walls = PostLatticeWalls();
  std::vector<Pose2> tour;
  for (int i = 0; i < 12; ++i)
    tour.push_back(Pose2{0.45 * std::cos(i), 0.45 * std::sin(i), 1.0 * i});
  const ProbabilityGrid grid = ScannedGrid(walls, tour, o);
  const PrecomputationGridStack grids(grid, o.search.depth);
  const Pose2 truth{0.3, -0.4, 0.2};
  const std::vector<Vec2> points = ScanPoints(walls, truth, o, 3, FullCircleLaser(361, 4.0));
  const BranchAndBoundResult r = SearchAtOnce(grids, points, Pose2{0.6, -0.2, 0.25}, o.search);
  ASSERT_TRUE(r.best.found);
  ASSERT_TRUE(r.runner_up.found);
  // Under half the room's (FindsAScanInARoom...: 0.124 of 0.605; here 0.055 of 0.710).
  EXPECT_LT(r.margin, 0.07);
  // The runner-up is a lattice step away.
  const double dx = r.runner_up.pose.x - r.best.pose.x, dy = r.runner_up.pose.y - r.best.pose.y;
  EXPECT_NEAR(std::hypot(dx, dy), 1.0, 0.15);
  std::cout << "lattice: score " << r.best.score << " runner-up " << r.runner_up.score << "\n";
}

TEST(BranchAndBound, MatchesASubmapsOccupiedCells) {
  const GridOptions o;
  const std::vector<sim::Wall> walls = RoomWalls();
  const ProbabilityGrid target = ScannedGrid(walls, RoomTour(), o);
  // A second submap whose frame is `truth` in the target's frame, built from other poses.
  const Pose2 truth{0.8, -0.5, 0.3};
  const std::vector<Vec2> points = OtherSubmapPoints(walls, 1.0, truth, o);
  ASSERT_GT(points.size(), 200u);
  const PrecomputationGridStack grids(target, o.search.depth);
  const BranchAndBoundResult r = SearchAtOnce(grids, points, Pose2{0.0, 0.0, 0.0}, o.search);
  ASSERT_TRUE(r.best.found);
  EXPECT_NEAR(r.best.pose.x, truth.x, 0.05);
  EXPECT_NEAR(r.best.pose.y, truth.y, 0.05);
  EXPECT_NEAR(r.best.pose.theta, truth.theta, 0.01);
}

TEST(BranchAndBound, NothingBelowTheMinimumScoreIsReturned) {
  const RandomCase c = MakeRandomCase(3);
  BranchAndBoundOptions o = SmallWindow(3);
  o.min_score = 0.95;
  const PrecomputationGridStack grids(c.grid, o.depth);
  BranchAndBoundSearch search(grids, c.points, c.center, o);
  EXPECT_EQ(search.Run(std::numeric_limits<int64_t>::max()), SearchStatus::kDone);
  EXPECT_FALSE(search.result().best.found);
  EXPECT_FALSE(search.result().runner_up.found);
  EXPECT_EQ(search.result().margin, 0.0);
  BranchAndBoundSearch empty(grids, {}, c.center, o);
  EXPECT_TRUE(empty.done());
}

}  // namespace
}  // namespace atlas
