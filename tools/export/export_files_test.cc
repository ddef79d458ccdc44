#include "tools/export/export_files.h"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <numbers>

#include "formats/g2o.h"
#include "formats/occupancy_grid.h"
#include "formats/ply_points.h"
#include "formats/tum_trajectory.h"

namespace atlas::exporter {
namespace {

using ::testing::HasSubstr;

// Frames 0 - 1 - 2 in a chain and frame 3 on its own; frame 1 is 2 m ahead of frame 0 and
// turned a quarter turn, frame 2 1 m ahead of frame 1.
formats::ReplayOutput ChainAndIsland() {
  formats::ReplayOutput run;
  const Mat3 cov = Vec3(0.01, 0.02, 0.001).asDiagonal();
  run.graph.edges = {{0, 1, {Pose2{2, 0, std::numbers::pi / 2}, cov}, EdgeKind::kGenesis},
                     {1, 2, {Pose2{1, 0, 0}, cov}, EdgeKind::kMapMatch}};
  run.trajectory = {{FromSeconds(1.0), 0, Pose2{0.5, 0, 0}, 1},
                    {FromSeconds(2.0), 2, Pose2{0, 0, 0}, 2},
                    {FromSeconds(3.0), 3, Pose2{0, 0, 0}, 3}};
  run.points = {{0, Vec2(1, 1)}, {1, Vec2(1, 0)}, {3, Vec2(5, 5)}};
  run.frame_count = 4;
  return run;
}

TEST(ExportFiles, PlacesFramesFromTheReferenceAndLeavesTheIslandOut) {
  ExportFiles f;
  ASSERT_EQ(MakeExportFiles(ChainAndIsland(), ExportOptions{}, "map.pgm", &f), "");
  EXPECT_EQ(f.frames, 4);
  EXPECT_EQ(f.placed_frames, 3);
  EXPECT_EQ(f.edges_written, 2);

  formats::G2oGraph g;
  ASSERT_EQ(formats::ParseG2o(f.g2o, "atlas.g2o", &g), "");
  ASSERT_EQ(g.vertices.size(), 3u);
  EXPECT_NEAR(g.vertices[2].pose.x, 2.0, 1e-6);  // frame 2: 1 m along frame 1's x, which is +y
  EXPECT_NEAR(g.vertices[2].pose.y, 1.0, 1e-6);
  ASSERT_EQ(g.edges.size(), 2u);
  EXPECT_NEAR(g.edges[0].information(0, 0), 100.0, 1e-4);  // 1 / 0.01
  EXPECT_NEAR(g.edges[0].information(2, 2), 1000.0, 1e-3);
  EXPECT_EQ(g.fixed, std::vector<int>{0});

  std::vector<eval::TimedPose> tum;
  ASSERT_TRUE(f.has_trajectory);
  ASSERT_EQ(formats::ParseTumTrajectory(f.tum, "t.tum", &tum), "");
  ASSERT_EQ(tum.size(), 2u);  // frame 3's row is left out
  EXPECT_EQ(f.trajectory_rows, 3);
  EXPECT_NEAR(tum[1].pose.x, 2.0, 1e-6);
  EXPECT_NEAR(tum[1].pose.y, 1.0, 1e-6);
  EXPECT_NEAR(tum[1].pose.theta, std::numbers::pi / 2, 1e-6);

  std::vector<formats::PlyPoint> cloud;
  ASSERT_EQ(formats::ParsePlyPoints(f.ply, "p.ply", &cloud), "");
  ASSERT_EQ(cloud.size(), 2u);
  EXPECT_NEAR(cloud[1].p.x(), 2.0, 1e-3);  // frame 1's (1, 0) is 1 m along +y from (2, 0)
  EXPECT_NEAR(cloud[1].p.y(), 1.0, 1e-3);

  formats::PgmImage image;
  ASSERT_EQ(formats::ParsePgm(f.pgm, "m.pgm", &image), "");
  EXPECT_EQ(image.width, f.grid_width);
  EXPECT_EQ(image.height, f.grid_height);
  EXPECT_EQ(f.occupied_cells, 2);
  int black = 0;
  for (uint8_t p : image.pixels) black += p == 0;
  EXPECT_EQ(black, 2);
  formats::MapYaml yaml;
  ASSERT_EQ(formats::ParseMapYaml(f.yaml, "m.yaml", &yaml), "");
  EXPECT_EQ(yaml.image, "map.pgm");
  EXPECT_DOUBLE_EQ(yaml.resolution, 0.1);
  // The points lie at (1, 1) and (2, 1) with a 1 m margin.
  EXPECT_NEAR(yaml.origin.x, 0.0, 1e-9);
  EXPECT_NEAR(yaml.origin.y, 0.0, 1e-9);
}

TEST(ExportFiles, AnotherReferenceFrame) {
  ExportOptions o;
  o.reference = 1;
  ExportFiles f;
  ASSERT_EQ(MakeExportFiles(ChainAndIsland(), o, "map.pgm", &f), "");
  formats::G2oGraph g;
  ASSERT_EQ(formats::ParseG2o(f.g2o, "atlas.g2o", &g), "");
  ASSERT_EQ(g.vertices.size(), 3u);
  // Frame 0 in frame 1: the inverse of (2, 0, pi/2) is (0, 2, -pi/2).
  EXPECT_NEAR(g.vertices[0].pose.x, 0.0, 1e-6);
  EXPECT_NEAR(g.vertices[0].pose.y, 2.0, 1e-6);
  EXPECT_NEAR(g.vertices[0].pose.theta, -std::numbers::pi / 2, 1e-6);
  EXPECT_NEAR(g.vertices[1].pose.x, 0.0, 1e-12);
  EXPECT_EQ(g.fixed, std::vector<int>{1});
}

TEST(ExportFiles, RefusesAFrameTheAtlasDoesNotHave) {
  ExportOptions o;
  o.reference = 9;
  ExportFiles f;
  EXPECT_EQ(MakeExportFiles(ChainAndIsland(), o, "map.pgm", &f),
            "the atlas has 4 frames (0..3), no frame 9");
}

TEST(ExportFiles, WithoutTrajectoryOrPoints) {
  formats::ReplayOutput run = ChainAndIsland();
  run.trajectory.clear();
  run.points.clear();
  ExportFiles f;
  ASSERT_EQ(MakeExportFiles(run, ExportOptions{}, "map.pgm", &f), "");
  EXPECT_FALSE(f.has_trajectory);
  EXPECT_FALSE(f.has_points);
  EXPECT_TRUE(f.tum.empty());
  EXPECT_TRUE(f.pgm.empty());
  EXPECT_THAT(f.g2o, HasSubstr("VERTEX_SE2 2 "));
}

}  // namespace
}  // namespace atlas::exporter
