#include "daemon/atlasd/atlas_checkpoint.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <functional>
#include <iterator>
#include <set>
#include <string>
#include <vector>

#include "core/mapper/mapper_factory.h"
#include "core/testing/atlas_test_world.h"
#include "core/testing/fake_local_map.h"
#include "core/testing/grid_scenes.h"
#include "daemon/atlasd/atlas_export.h"
#include "daemon/atlasd/daemon_setup.h"
#include "formats/replay_dir.h"
#include "formats/text_rows.h"
#include "sim/corridor.h"

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
  // The store files moved aside as corrupt (atlas.sqlite.corrupt-*).
  int CorruptFilesMovedAside() const {
    int moved = 0;
    for (const auto& e : fs::directory_iterator(dir_))
      moved += e.path().filename().string().find("atlas.sqlite.corrupt-") == 0;
    return moved;
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
    // Nothing moved: the next batch carries the image alone.
    AtlasSnapshot again = builder.Make(*a);
    EXPECT_TRUE(again.edges.empty());
    EXPECT_TRUE(again.frames.empty());
    EXPECT_EQ(again.metadata.count("atlas_image"), 1u);
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

// A grid atlas down a corridor and back, saved every few steps (the intervals vary): after
// every batch the store loads back into the atlas as it is, byte for byte (its whole
// Serialize()), although each batch carries only the maps that changed, among them frames
// whose hypothesis left since the batch before (not new, no hypothesis when the batch is made).
TEST_F(CheckpointTest, EveryCheckpointOfAGridAtlasLoadsBackWhole) {
  MapperSettings settings;
  settings.grid_frames = true;
  std::unique_ptr<Atlas> a = MakeAtlas(settings);
  FakeWallScanner scanner(sim::CorridorWalls(40.0), FrontLaser(), 4);
  AtlasStore store;
  ASSERT_TRUE(store.Open(dir_.string()).ok());
  CheckpointBuilder builder;
  Pose2 robot;
  a->Step(Pose2{}, scanner.Scan(robot));
  const int kPeriods[] = {7, 3, 11, 5};
  int batches = 0, partial = 0, left = 0, frames_sent_before = 0;
  for (int i = 1, next = 5; i <= 520; ++i) {
    const Pose2 u{i <= 360 ? 0.1 : -0.1, 0.0, 0.0};
    robot = Compose(robot, u);
    a->Step(u, scanner.Scan(robot));
    if (i < next) continue;
    next = i + kPeriods[batches % 4];
    const AtlasSnapshot b = builder.Make(*a);
    std::string error;
    ASSERT_TRUE(store.Save(b, &error)) << error;
    ++batches;
    const int frames = a->Graph().FrameCount();
    partial += static_cast<int>(b.frames.size()) < frames;
    for (const StoredFrame& row : b.frames) {
      bool held = false;
      for (const Hypothesis& h : a->Hypotheses()) held = held || h.frame == row.id;
      left += row.id < frames_sent_before && !held;
    }
    frames_sent_before = frames;
    StoredAtlas saved;
    ASSERT_TRUE(store.Load(&saved, &error)) << error;
    std::unique_ptr<Atlas> loaded = MakeAtlas(settings);
    ASSERT_EQ(LoadSavedAtlas(saved, loaded.get()), "") << "batch " << batches;
    ASSERT_TRUE(loaded->Serialize() == a->Serialize()) << "batch " << batches;
  }
  EXPECT_GE(a->Graph().FrameCount(), 4);
  EXPECT_GT(partial, batches / 2);
  EXPECT_GT(left, 0);
}

// A checkpoint after steps that changed no frame's map (steps whose input was refused) carries
// the image and no frame row; after a step, the rows of the frames a mature hypothesis held.
TEST_F(CheckpointTest, NoFrameRowWhenNoMapChanged) {
  auto a = NewAtlas();
  Drive(a.get(), 60);
  CheckpointBuilder builder;
  EXPECT_EQ(static_cast<int>(builder.Make(*a).frames.size()), a->Graph().FrameCount());
  for (int i = 0; i < 3; ++i)
    ASSERT_EQ(a->Step(Pose2{NAN, 0.0, 0.0}, TestScan()).rejected_input, 1);
  AtlasSnapshot b = builder.Make(*a);
  EXPECT_TRUE(b.frames.empty());
  EXPECT_TRUE(b.edges.empty());
  EXPECT_EQ(b.metadata["atlas_steps"], "63");
  // The frames a mature hypothesis held before or after the step, and new frames.
  std::set<FrameId> mature;
  const auto add_mature = [&]() {
    for (const Hypothesis& h : a->Hypotheses())
      if (h.state == HypothesisState::kMature) mature.insert(h.frame);
  };
  add_mature();
  const int frames = a->Graph().FrameCount();
  Drive(a.get(), 1);
  add_mature();
  for (FrameId f = frames; f < a->Graph().FrameCount(); ++f) mature.insert(f);
  b = builder.Make(*a);
  std::set<FrameId> rows;
  for (const StoredFrame& f : b.frames) rows.insert(f.id);
  EXPECT_EQ(rows, mature);
}

// A version 6 image whose frame has no row, or a row that does not decode, is refused as
// corrupt, naming the frame, and the store is moved aside.
TEST_F(CheckpointTest, MissingOrUndecodableFrameRowIsRefusedAsCorrupt) {
  auto a = NewAtlas();
  Drive(a.get(), 60);
  ASSERT_GE(a->Graph().FrameCount(), 3);
  const AtlasSnapshot whole = CheckpointBuilder().Make(*a);
  struct Case {
    const char* name;
    std::function<void(AtlasSnapshot*)> damage;
    std::string message;
  };
  const std::vector<Case> cases = {
      {"missing",
       [](AtlasSnapshot* b) {
         std::erase_if(b->frames, [](const StoredFrame& f) { return f.id == 1; });
       },
       "its atlas image keeps the map of frame 1 in the frames table, which has no row for it"},
      {"undecodable", [](AtlasSnapshot* b) { b->frames[2].blob = "not a map"; },
       "the map of frame 2 (its row in the frames table, 9 bytes) does not decode with this "
       "configuration"},
  };
  int moved_before = 0;
  for (const Case& c : cases) {
    SCOPED_TRACE(c.name);
    AtlasStore store;
    ASSERT_TRUE(store.Open(dir_.string()).ok());
    AtlasSnapshot b = whole;
    c.damage(&b);
    std::string error;
    ASSERT_TRUE(store.Save(b, &error)) << error;
    auto fresh = NewAtlas();
    CheckpointBuilder builder;
    const ResumeResult r = ResumeFromStore(&store, fresh.get(), &builder);
    EXPECT_EQ(r.outcome, ResumeOutcome::kRefusedCorrupt) << r.message;
    EXPECT_NE(r.message.find(c.message), std::string::npos) << r.message;
    EXPECT_NE(r.message.find("moved it aside"), std::string::npos) << r.message;
    EXPECT_EQ(r.message.find('\n'), std::string::npos) << r.message;
    EXPECT_EQ(fresh->Graph().FrameCount(), 0);
    const int moved = CorruptFilesMovedAside();
    EXPECT_EQ(moved, moved_before + 1);
    moved_before = moved;
    StoredAtlas now;
    ASSERT_TRUE(store.Load(&now, &error));
    EXPECT_EQ(now.metadata.count("atlas_image"), 0u);
  }
}

// A store written before the frames' maps were kept apart (image version 5: every map in the
// image; its frame rows may be behind it) resumes as it did, and the first batch after it
// writes every frame's row; after a version 6 resume, the first batch writes only the new
// frame's.
TEST_F(CheckpointTest, Version5StoreStillResumes) {
  auto a = NewAtlas();
  Drive(a.get(), 60);
  std::string v5 = a->Serialize();
  const uint32_t five = 5;
  std::memcpy(v5.data() + 4, &five, sizeof(five));
  {
    AtlasStore store;
    ASSERT_TRUE(store.Open(dir_.string()).ok());
    AtlasSnapshot b;
    b.metadata["atlas_image"] = v5;
    b.metadata["atlas_image_version"] = "5";
    b.metadata["atlas_steps"] = "60";
    b.frames = {{0, "a row behind the image", 0}};
    std::string error;
    ASSERT_TRUE(store.Save(b, &error)) << error;
    StoredAtlas saved;
    ASSERT_TRUE(store.Load(&saved, &error)) << error;
    auto loaded = NewAtlas();
    ASSERT_EQ(LoadSavedAtlas(saved, loaded.get()), "");
    EXPECT_TRUE(loaded->Serialize() == a->Serialize());
  }
  AtlasStore store;
  ASSERT_TRUE(store.Open(dir_.string()).ok());
  auto b = NewAtlas();
  CheckpointBuilder builder;
  const ResumeResult r = ResumeFromStore(&store, b.get(), &builder);
  ASSERT_EQ(r.outcome, ResumeOutcome::kResumed) << r.message;
  EXPECT_EQ(r.frames, a->Graph().FrameCount());
  const AtlasSnapshot first = builder.Make(*b);
  EXPECT_EQ(static_cast<int>(first.frames.size()), b->Graph().FrameCount());
  std::string error;
  ASSERT_TRUE(store.Save(first, &error)) << error;

  // Now version 6: resumed again, only the robot's new frame is new.
  AtlasStore again;
  store.Close();
  ASSERT_TRUE(again.Open(dir_.string()).ok());
  auto c = NewAtlas();
  CheckpointBuilder next;
  const ResumeResult r6 = ResumeFromStore(&again, c.get(), &next);
  ASSERT_EQ(r6.outcome, ResumeOutcome::kResumed) << r6.message;
  const AtlasSnapshot after = next.Make(*c);
  ASSERT_EQ(after.frames.size(), 1u);
  EXPECT_EQ(after.frames[0].id, r6.new_frame);
  EXPECT_TRUE(after.edges.empty());
}

// --export-atlas reads both: a version 5 store and the same atlas saved as version 6 give the
// same files.
TEST_F(CheckpointTest, ExportReadsVersion5And6Stores) {
  DaemonOptions options;
  options.localmap.kind = LocalMapKind::kGrid;
  std::unique_ptr<Atlas> a = MakeAtlas(ToMapperSettings(options));
  FakeWallScanner scanner(sim::CorridorWalls(), FrontLaser(), 5);
  for (int i = 0; i < 40; ++i) a->Step(Pose2{0.1, 0.0, 0.0}, scanner.Scan({0.1 * i, 0, 0}));
  std::string v5 = a->Serialize();
  const uint32_t five = 5;
  std::memcpy(v5.data() + 4, &five, sizeof(five));
  AtlasSnapshot old_store;
  old_store.metadata = {{"atlas_image", v5}, {"atlas_image_version", "5"}, {"atlas_steps", "40"}};
  std::vector<std::string> files[2];
  int version = 5;
  for (const AtlasSnapshot& b : {old_store, CheckpointBuilder().Make(*a)}) {
    SCOPED_TRACE("version " + std::to_string(version));
    options.state.directory = (dir_ / ("v" + std::to_string(version))).string();
    {
      AtlasStore store;
      ASSERT_TRUE(store.Open(options.state.directory).ok());
      std::string error;
      ASSERT_TRUE(store.Save(b, &error)) << error;
    }
    const fs::path out = dir_ / ("out" + std::to_string(version));
    ASSERT_EQ(ExportSavedAtlas(options, out.string()), 0);
    for (const char* name : {"graph.tsv", "maps.tsv", "points.tsv"}) {
      std::ifstream in(out / name);
      files[version - 5].emplace_back(std::istreambuf_iterator<char>(in),
                                      std::istreambuf_iterator<char>());
    }
    ++version;
  }
  EXPECT_GT(files[0][2].size(), 1000u);  // the grid's occupied cells
  EXPECT_EQ(files[0], files[1]);
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
  EXPECT_EQ(CorruptFilesMovedAside(), 1);
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
  EXPECT_EQ(CorruptFilesMovedAside(), static_cast<int>(bad.size()));
}

}  // namespace
}  // namespace atlas
