#include "daemon/atlasd/atlas_checkpoint.h"

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include "core/mapper/mapper_factory.h"
#include "core/testing/atlas_test_world.h"
#include "core/testing/fake_local_map.h"
#include "core/testing/grid_scenes.h"
#include "daemon/atlasd/atlas_export.h"
#include "formats/replay_dir.h"
#include "formats/text_rows.h"

namespace atlas {
namespace {

namespace fs = std::filesystem;

class CheckpointTest : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = fs::path(::testing::TempDir()) /
           ("checkpoint_" +
            std::string(::testing::UnitTest::GetInstance()->current_test_info()->name()));
    fs::remove_all(dir_);
  }
  void TearDown() override { fs::remove_all(dir_); }
  std::unique_ptr<Atlas> NewAtlas() {
    return std::make_unique<Atlas>(TestWorld::Options(), world_.Factory(),
                                   std::make_shared<FakeBootstrapper>());
  }
  // Drives far enough for Genesis to make several frames.
  static void Drive(Atlas* a, int steps) {
    for (int i = 0; i < steps; ++i) a->Step(Pose2{0.25, 0.0, 0.0}, TestScan());
  }
  TestWorld world_;
  fs::path dir_;
};

TEST_F(CheckpointTest, SavedAtlasIsResumedWhole) {
  auto a = NewAtlas();
  Drive(a.get(), 60);
  ASSERT_GE(a->Graph().FrameCount(), 2);
  {
    AtlasStore store;
    ASSERT_TRUE(store.Open(dir_.string()).ok());
    CheckpointBuilder builder;
    AtlasSnapshot first = builder.Make(*a);
    EXPECT_EQ(static_cast<int>(first.frames.size()), a->Graph().FrameCount());
    EXPECT_EQ(static_cast<int>(first.edges.size()), a->Graph().EdgeCount());
    std::string error;
    ASSERT_TRUE(store.Save(first, &error)) << error;
    // Nothing moved: the next batch carries the image and the frames with hypotheses only.
    AtlasSnapshot again = builder.Make(*a);
    EXPECT_TRUE(again.edges.empty());
    EXPECT_LE(again.frames.size(), a->Hypotheses().size());
    ASSERT_TRUE(store.Save(again, &error)) << error;
  }
  AtlasStore store;
  ASSERT_EQ(store.Open(dir_.string()).status, StoreOpenStatus::kOpened);
  auto b = NewAtlas();
  const ResumeResult r = ResumeFromStore(&store, b.get());
  ASSERT_EQ(r.outcome, ResumeOutcome::kResumed) << r.message;
  EXPECT_EQ(r.frames, a->Graph().FrameCount());
  EXPECT_EQ(r.steps, 60);
  // The saved frames and edges as they were, and the robot alone in a new frame at the origin.
  ASSERT_EQ(b->Graph().FrameCount(), a->Graph().FrameCount() + 1);
  EXPECT_EQ(r.new_frame, a->Graph().FrameCount());
  for (FrameId f = 0; f < a->Graph().FrameCount(); ++f)
    EXPECT_TRUE(b->Graph().Frame(f).map->Serialize() == a->Graph().Frame(f).map->Serialize());
  EXPECT_EQ(b->Graph().EdgeCount(), a->Graph().EdgeCount());
  ASSERT_TRUE(b->Dominant().valid);
  EXPECT_EQ(b->Dominant().frame, r.new_frame);
  EXPECT_EQ(b->Dominant().pose.mean.x, 0.0);
  StoredAtlas saved;
  std::string error;
  ASSERT_TRUE(store.Load(&saved, &error));
  EXPECT_EQ(static_cast<int>(saved.frames.size()), a->Graph().FrameCount());
}

TEST_F(CheckpointTest, ExportWritesOneGraphRowPerEdgeAndOneMapRowPerLine) {
  auto a = NewAtlas();
  Drive(a.get(), 60);
  ASSERT_EQ(WriteAtlasFiles(*a, dir_.string()), "");
  auto rows = [&](const char* name) {
    std::ifstream in(dir_ / name);
    std::string line;
    int n = 0;
    while (std::getline(in, line)) n += !line.empty() && line[0] != '#';
    return n;
  };
  EXPECT_EQ(rows("graph.tsv"), a->Graph().EdgeCount());
  size_t lines = 0;
  for (FrameId f = 0; f < a->Graph().FrameCount(); ++f)
    lines += a->Graph().Frame(f).map->Lines().size();
  EXPECT_EQ(rows("maps.tsv"), static_cast<int>(lines));
  int cells = 0;
  for (FrameId f = 0; f < a->Graph().FrameCount(); ++f) cells += a->Graph().Frame(f).points.Size();
  EXPECT_EQ(rows("points.tsv"), cells);
}

// Grid frames keep no laser points and have no lines: points.tsv holds each frame's occupied
// cells, in the frame's coordinates, where the walls the robot scanned are.
TEST_F(CheckpointTest, ExportWritesAGridFramesOccupiedCellsAsItsPoints) {
  MapperSettings s;
  s.grid_frames = true;
  std::unique_ptr<Atlas> a = MakeAtlas(s);
  const std::vector<sim::Wall> walls = RoomWalls();
  FakeWallScanner scanner(walls, FrontLaser(), 2);
  // Frame 0's origin is the first pose, the room's centre: frame 0 is the room's coordinates.
  Pose2 robot;
  a->Step(Pose2{}, scanner.Scan(robot));
  const Pose2 u{0.2, 0.0, 0.3};  // a circle of 0.7 m radius, looking all around
  for (int k = 0; k < 20; ++k) {
    robot = Compose(robot, u);
    a->Step(u, scanner.Scan(robot));
  }
  ASSERT_EQ(a->Graph().FrameCount(), 1);
  ASSERT_EQ(WriteAtlasFiles(*a, dir_.string()), "");
  const formats::TextFile file = formats::ReadTextFile((dir_ / "points.tsv").string());
  ASSERT_EQ(file.error, "");
  std::vector<formats::FramePointRow> points;
  ASSERT_EQ(formats::ParsePointRows(file.text, "points.tsv", &points), "");
  ASSERT_GT(points.size(), 500u);
  EXPECT_LE(points.size(), static_cast<size_t>(formats::kMaxMapPointsPerFrame));
  int south = 0, pillar = 0;
  for (const formats::FramePointRow& r : points) {
    EXPECT_EQ(r.frame, 0);
    EXPECT_LT(DistanceToWalls(r.p, walls), 0.1) << r.p.transpose();
    south += std::abs(r.p.y() + 4.0) < 0.1;
    pillar += r.p.x() > 1.9 && r.p.x() < 2.5 && r.p.y() > -2.6 && r.p.y() < -2.0;
  }
  EXPECT_GT(south, 100);  // 10 m of wall in 5 cm cells, most of it seen
  EXPECT_GT(pillar, 10);
}

// --export-atlas only reads: a missing store is not created, a corrupt one is not moved aside.
TEST_F(CheckpointTest, ExportOfAMissingOrCorruptStoreChangesNothing) {
  DaemonOptions options;
  options.state.directory = (dir_ / "state").string();
  const fs::path out = dir_ / "out";
  EXPECT_EQ(ExportSavedAtlas(options, out.string()), 1);
  EXPECT_FALSE(fs::exists(options.state.directory));
  EXPECT_FALSE(fs::exists(out));

  fs::create_directories(options.state.directory);
  const fs::path file = fs::path(options.state.directory) / AtlasStore::kFileName;
  EXPECT_EQ(ExportSavedAtlas(options, out.string()), 1);
  EXPECT_TRUE(fs::is_empty(options.state.directory));

  const std::string garbage(5000, 'x');
  std::ofstream(file, std::ios::binary) << garbage;
  EXPECT_EQ(ExportSavedAtlas(options, out.string()), 1);
  int names = 0;
  for (const auto& e : fs::directory_iterator(options.state.directory)) {
    EXPECT_EQ(e.path(), file);
    ++names;
  }
  EXPECT_EQ(names, 1);
  std::ifstream in(file, std::ios::binary);
  EXPECT_EQ(std::string(std::istreambuf_iterator<char>(in), {}), garbage);
  EXPECT_FALSE(fs::exists(out));
}

TEST_F(CheckpointTest, EmptyStoreLeavesTheAtlasEmpty) {
  AtlasStore store;
  ASSERT_TRUE(store.Open(dir_.string()).ok());
  auto a = NewAtlas();
  const ResumeResult r = ResumeFromStore(&store, a.get());
  EXPECT_EQ(r.outcome, ResumeOutcome::kEmpty) << r.message;
  EXPECT_EQ(a->Graph().FrameCount(), 0);
}

TEST_F(CheckpointTest, UndecodableImageIsMovedAsideNotOverwritten) {
  AtlasStore store;
  ASSERT_TRUE(store.Open(dir_.string()).ok());
  auto a = NewAtlas();
  Drive(a.get(), 10);
  AtlasSnapshot b = CheckpointBuilder().Make(*a);
  b.metadata["atlas_image"].resize(b.metadata["atlas_image"].size() / 2);
  std::string error;
  ASSERT_TRUE(store.Save(b, &error)) << error;
  auto fresh = NewAtlas();
  const ResumeResult r = ResumeFromStore(&store, fresh.get());
  EXPECT_EQ(r.outcome, ResumeOutcome::kRefusedCorrupt);
  EXPECT_NE(r.message.find("does not decode"), std::string::npos) << r.message;
  EXPECT_NE(r.message.find("moved it aside"), std::string::npos) << r.message;
  EXPECT_EQ(fresh->Graph().FrameCount(), 0);
  int moved = 0;
  for (const auto& e : fs::directory_iterator(dir_))
    moved += e.path().filename().string().find("atlas.sqlite.corrupt-") == 0;
  EXPECT_EQ(moved, 1);
  StoredAtlas now;
  ASSERT_TRUE(store.Load(&now, &error));
  EXPECT_EQ(now.metadata.count("atlas_image"), 0u);  // the new store is empty
}

TEST_F(CheckpointTest, NewerImageVersionIsRefused) {
  AtlasStore store;
  ASSERT_TRUE(store.Open(dir_.string()).ok());
  auto a = NewAtlas();
  Drive(a.get(), 10);
  AtlasSnapshot b = CheckpointBuilder().Make(*a);
  b.metadata["atlas_image_version"] = std::to_string(Atlas::kImageVersion + 1);
  std::string error;
  ASSERT_TRUE(store.Save(b, &error)) << error;
  auto fresh = NewAtlas();
  const ResumeResult r = ResumeFromStore(&store, fresh.get());
  EXPECT_EQ(r.outcome, ResumeOutcome::kRefusedNewer);
  EXPECT_NE(r.message.find("newer atlasd"), std::string::npos) << r.message;
  EXPECT_EQ(fresh->Graph().FrameCount(), 0);
}

// The image itself decodes; only its version text is damaged. strtol read "abc" as 0 (and
// resumed) and "99999999999999999999" as LONG_MAX (refused as newer).
TEST_F(CheckpointTest, UnreadableImageVersionIsRefusedAsCorrupt) {
  AtlasStore store;
  ASSERT_TRUE(store.Open(dir_.string()).ok());
  auto a = NewAtlas();
  Drive(a.get(), 10);
  const std::vector<std::string> bad = {
      "abc", "1x", "", " 5", "-1", "4294967296", "99999999999999999999"};
  for (const std::string& version : bad) {
    SCOPED_TRACE("atlas_image_version '" + version + "'");
    AtlasSnapshot b = CheckpointBuilder().Make(*a);
    b.metadata["atlas_image_version"] = version;
    std::string error;
    ASSERT_TRUE(store.Save(b, &error)) << error;
    auto fresh = NewAtlas();
    const ResumeResult r = ResumeFromStore(&store, fresh.get());
    EXPECT_EQ(r.outcome, ResumeOutcome::kRefusedCorrupt) << r.message;
    EXPECT_NE(r.message.find("its atlas image version (atlas_image_version, " +
                             std::to_string(version.size()) +
                             " bytes) is not a decimal integer in [0, 4294967295]"),
              std::string::npos)
        << r.message;
    EXPECT_NE(r.message.find("moved it aside"), std::string::npos) << r.message;
    EXPECT_EQ(fresh->Graph().FrameCount(), 0);
  }
  int moved = 0;
  for (const auto& e : fs::directory_iterator(dir_))
    moved += e.path().filename().string().find("atlas.sqlite.corrupt-") == 0;
  EXPECT_EQ(moved, static_cast<int>(bad.size()));
}

}  // namespace
}  // namespace atlas
