#include "formats/replay_dir.h"

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>

namespace atlas::formats {
namespace {

TEST(ReplayDir, ParsesWhatReplayWrites) {
  std::vector<FrameLine> lines;
  ASSERT_EQ(ParseMapRows("3\t7\t2.5\t0.1\t1\t2\t3\t4\t1e-4\t1e-6\t1e-5\n", "maps.tsv", &lines), "");
  ASSERT_EQ(lines.size(), 1u);
  EXPECT_EQ(lines[0].frame, 3);
  EXPECT_EQ(lines[0].line.id, 7);
  EXPECT_DOUBLE_EQ(lines[0].line.endpoint_b.y(), 4.0);
  EXPECT_DOUBLE_EQ(lines[0].line.cov(1, 0), 1e-6);

  std::vector<FramePointRow> points;
  ASSERT_EQ(ParsePointRows("2\t-0.05\t1.35\n", "points.tsv", &points), "");
  ASSERT_EQ(points.size(), 1u);
  EXPECT_EQ(points[0].frame, 2);
  EXPECT_DOUBLE_EQ(points[0].p.x(), -0.05);
  EXPECT_EQ(ParsePointRows("2\t0.1\n", "points.tsv", &points),
            "points.tsv:1: expected 3 fields (frame x y), found 2");
  EXPECT_NE(ParsePointRows("-4\t0.1\t0.2\n", "points.tsv", &points), "");

  std::vector<FrameRecord> frames;
  ASSERT_EQ(ParseFrameRows("0\t1\t10.5\t-1\n1\t40\t12.0\t0\n", "frames.tsv", &frames), "");
  EXPECT_EQ(frames[0].parent, kNoFrame);
  EXPECT_EQ(frames[1].step, 40);
}

// The files of one directory must agree, and a file a picture needs must hold rows.
TEST(ReplayDir, ReadReplayOutputChecksTheFilesAgree) {
  const std::filesystem::path dir =
      std::filesystem::path(::testing::TempDir()) / "replay_dir_agree_test";
  std::filesystem::remove_all(dir);
  std::filesystem::create_directories(dir);
  const auto write = [&](const char* name, const std::string& text) {
    std::ofstream(dir / name) << text;
  };
  const std::string edge = "0 1 1 0 0 0.01 0 0 0.01 0 0.001 genesis\n";
  write("trajectory.tsv", "# h\n1.0 0 0 0 0\n2.0 1 0 0 0\n");
  write("graph.tsv", "# h\n" + edge);
  write("frames.tsv", "# h\n0 1 1.0 -1\n1 2 2.0 0\n");
  ReplayOutput run;
  ASSERT_EQ(ReadReplayOutput(dir.string(), ReplayFilesWanted{}, &run), "");
  EXPECT_EQ(run.frame_count, 2);
  EXPECT_EQ(run.graph.lines[0], 2);

  // An edge to a frame the run does not have.
  write("graph.tsv", "# h\n" + edge + "1 9 1 0 0 0.01 0 0 0.01 0 0.001 map-match\n");
  EXPECT_EQ(ReadReplayOutput(dir.string(), ReplayFilesWanted{}, &run),
            (dir / "graph.tsv").string() +
                ":3: edge 1-9 names frame 9, but the run has 2 frames (0..1, frames.tsv); the "
                "files are not from one run, or the row is damaged");
  // An empty graph for two frames; then for one frame (legitimate).
  write("graph.tsv", "# h\n");
  EXPECT_NE(ReadReplayOutput(dir.string(), ReplayFilesWanted{}, &run)
                .find("graph.tsv: no rows (the run has 2 frames"),
            std::string::npos);
  write("trajectory.tsv", "# h\n1.0 0 0 0 0\n");
  write("frames.tsv", "# h\n0 1 1.0 -1\n");
  EXPECT_EQ(ReadReplayOutput(dir.string(), ReplayFilesWanted{}, &run), "");
  // An empty trajectory; an empty global.tsv beside a trajectory with rows; maps wanted.
  write("trajectory.tsv", "# h\n");
  EXPECT_NE(
      ReadReplayOutput(dir.string(), ReplayFilesWanted{}, &run).find("trajectory.tsv: no rows"),
      std::string::npos);
  write("trajectory.tsv", "# h\n1.0 0 0 0 0\n");
  write("global.tsv", "# h\n");
  EXPECT_NE(ReadReplayOutput(dir.string(), ReplayFilesWanted{}, &run).find("global.tsv: no rows"),
            std::string::npos);
  std::filesystem::remove(dir / "global.tsv");
  write("maps.tsv", "# h\n");
  ReplayFilesWanted maps;
  maps.maps = true;
  EXPECT_NE(ReadReplayOutput(dir.string(), maps, &run).find("maps.tsv: no rows"),
            std::string::npos);
  // Points are a map to draw without lines (grid frames).
  write("points.tsv", "# h\n0 1.25 -4.05\n");
  EXPECT_EQ(ReadReplayOutput(dir.string(), maps, &run), "");
  EXPECT_EQ(run.points.size(), 1u);
  std::filesystem::remove_all(dir);
}

TEST(ReplayDir, GlobalTrajectory) {
  const std::vector<FramePoseRow> traj = {{FromSeconds(1.0), 0, Pose2{0.5, 0, 0}, 0},
                                          {FromSeconds(2.0), 1, Pose2{1, 0, 0}, 0},
                                          {FromSeconds(3.0), 2, Pose2{0, 0, 0}, 0}};
  const std::vector<std::optional<Pose2>> frames = {Pose2{}, Pose2{1, 0, M_PI / 2}, std::nullopt};
  int rows = 0;
  const std::string text = FormatGlobalTrajectory(traj, frames, "c", &rows);
  EXPECT_EQ(rows, 2);  // frame 2 has no pose
  EXPECT_EQ(text,
            "# c\n1.000000\t0.500000\t0.000000\t0.000000\n"
            "2.000000\t1.000000\t1.000000\t1.570796\n");
}

}  // namespace
}  // namespace atlas::formats
