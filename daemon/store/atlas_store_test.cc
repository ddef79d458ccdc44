#include "daemon/store/atlas_store.h"

#include <gmock/gmock.h>
#include <grp.h>
#include <gtest/gtest.h>
#include <signal.h>
#include <sqlite3.h>
#include <sys/wait.h>
#include <unistd.h>

#include <chrono>
#include <filesystem>
#include <fstream>
#include <functional>
#include <limits>
#include <random>
#include <thread>

#include "daemon/store/atlas_store_writer.h"

namespace atlas {
namespace {

namespace fs = std::filesystem;
using ::testing::HasSubstr;

// A fresh directory per test, removed afterwards.
class StoreDir : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = fs::path(testing::TempDir()) /
           ("atlas_store_" + std::to_string(getpid()) + "_" +
            testing::UnitTest::GetInstance()->current_test_info()->name());
    fs::remove_all(dir_);
  }
  void TearDown() override { fs::remove_all(dir_); }
  std::string db() const { return (dir_ / AtlasStore::kFileName).string(); }
  // A child process saves Batch(1..5) into the store and is killed (SIGKILL) right after.
  void SaveFiveBatchesThenSigkill();

  fs::path dir_;
};

// A byte image with NULs and every byte value, distinct per (id, version).
std::string Blob(int id, int version) {
  std::string s(200 + (id * 37 + version) % 900, '\0');
  for (size_t i = 0; i < s.size(); ++i)
    s[i] = static_cast<char>((i * 7 + id * 13 + version) & 0xff);
  return s;
}

StoredEdge Edge(int from, int to, double x) {
  StoredEdge e;
  e.frame_from = from;
  e.frame_to = to;
  e.x = x;
  e.y = -x / 2;
  e.theta = 0.25;
  for (int i = 0; i < 9; ++i) e.covariance[i] = 0.001 * (i + 1) + x;
  e.kind = 2;
  return e;
}

std::string ReadFile(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  return std::string(std::istreambuf_iterator<char>(in), {});
}

void SetSchemaVersion(const std::string& db, int version) {
  sqlite3* raw = nullptr;
  ASSERT_EQ(sqlite3_open(db.c_str(), &raw), SQLITE_OK);
  ASSERT_EQ(
      sqlite3_exec(raw, ("UPDATE schema_version SET version = " + std::to_string(version)).c_str(),
                   nullptr, nullptr, nullptr),
      SQLITE_OK);
  sqlite3_close(raw);
}

AtlasSnapshot Batch(int k);
void ExpectConsistentPrefix(const StoredAtlas& a, int last);

TEST_F(StoreDir, SaveLoadRoundTrip) {
  {
    AtlasStore store;
    const StoreOpenResult r = store.Open(dir_.string());
    ASSERT_EQ(r.status, StoreOpenStatus::kCreated) << r.message;
    AtlasSnapshot first;
    first.frames = {{0, Blob(0, 0), 0}, {1, Blob(1, 0), 0}};
    first.edges = {Edge(0, 1, 3.5)};
    first.metadata["next_frame_id"] = "2";
    std::string error;
    ASSERT_TRUE(store.Save(first, &error)) << error;
    AtlasSnapshot second;
    second.frames = {{1, Blob(1, 1), 0}, {2, Blob(2, 0), 0}};
    second.edges = {Edge(1, 2, -1.0), Edge(0, 1, 4.0)};
    ASSERT_TRUE(store.Save(second, &error)) << error;
  }
  AtlasStore store;
  const StoreOpenResult r = store.Open(dir_.string());
  ASSERT_EQ(r.status, StoreOpenStatus::kOpened) << r.message;
  StoredAtlas atlas;
  std::string error;
  ASSERT_TRUE(store.Load(&atlas, &error)) << error;
  ASSERT_EQ(atlas.frames.size(), 3u);
  EXPECT_EQ(atlas.frames[0].blob, Blob(0, 0));
  EXPECT_EQ(atlas.frames[1].blob, Blob(1, 1));  // updated by the second batch
  EXPECT_EQ(atlas.frames[2].blob, Blob(2, 0));
  EXPECT_GT(atlas.frames[2].updated_at, 1'600'000'000'000'000);  // Unix microseconds
  ASSERT_EQ(atlas.edges.size(), 2u);
  EXPECT_EQ(atlas.edges[0].frame_from, 0);
  EXPECT_DOUBLE_EQ(atlas.edges[0].x, 4.0);  // replaced
  EXPECT_DOUBLE_EQ(atlas.edges[0].y, -2.0);
  EXPECT_EQ(atlas.edges[0].covariance, Edge(0, 1, 4.0).covariance);
  EXPECT_EQ(atlas.edges[1].frame_to, 2);
  EXPECT_EQ(atlas.edges[1].kind, 2);
  EXPECT_EQ(atlas.metadata["next_frame_id"], "2");
  EXPECT_EQ(atlas.metadata["batch_sequence"], "2");
}

TEST_F(StoreDir, BinaryMetadataRoundTripsExactly) {
  std::string image("\x00\x01atlas\x00\xff\xfe", 10);
  {
    AtlasStore store;
    ASSERT_TRUE(store.Open(dir_.string()).ok());
    AtlasSnapshot b;
    b.metadata["atlas_image"] = image;
    std::string error;
    ASSERT_TRUE(store.Save(b, &error)) << error;
  }
  AtlasStore store;
  ASSERT_EQ(store.Open(dir_.string()).status, StoreOpenStatus::kOpened);
  StoredAtlas a;
  std::string error;
  ASSERT_TRUE(store.Load(&a, &error)) << error;
  EXPECT_EQ(a.metadata["atlas_image"], image);
  EXPECT_EQ(a.metadata["batch_sequence"], "1");
}

TEST_F(StoreDir, RefusedContentIsMovedAsideAndAnEmptyStoreOpened) {
  AtlasStore store;
  ASSERT_TRUE(store.Open(dir_.string()).ok());
  AtlasSnapshot b;
  b.metadata["atlas_image"] = "not an image";
  std::string error;
  ASSERT_TRUE(store.Save(b, &error)) << error;
  const StoreOpenResult r = store.RefuseAndStartEmpty(false, "its atlas image does not decode");
  ASSERT_EQ(r.status, StoreOpenStatus::kMovedAsideCorrupt) << r.message;
  EXPECT_NE(r.message.find("does not decode"), std::string::npos) << r.message;
  ASSERT_TRUE(fs::exists(r.moved_to));
  StoredAtlas a;
  ASSERT_TRUE(store.Load(&a, &error)) << error;
  EXPECT_TRUE(a.metadata.empty());
  // The moved file still holds what was saved.
  sqlite3* db = nullptr;
  ASSERT_EQ(sqlite3_open_v2(r.moved_to.c_str(), &db, SQLITE_OPEN_READONLY, nullptr), SQLITE_OK);
  sqlite3_stmt* st = nullptr;
  ASSERT_EQ(sqlite3_prepare_v2(db, "SELECT count(*) FROM metadata WHERE key = 'atlas_image'", -1,
                               &st, nullptr),
            SQLITE_OK);
  ASSERT_EQ(sqlite3_step(st), SQLITE_ROW);
  EXPECT_EQ(sqlite3_column_int(st, 0), 1);
  sqlite3_finalize(st);
  sqlite3_close(db);
}

TEST_F(StoreDir, NotADatabaseIsRefusedAndMovedAsideNeverOverwritten) {
  fs::create_directories(dir_);
  std::string garbage(5000, 'x');
  garbage.replace(0, 20, "this is not sqlite!\n");
  std::ofstream(db(), std::ios::binary) << garbage;
  AtlasStore store;
  const StoreOpenResult r = store.Open(dir_.string());
  ASSERT_EQ(r.status, StoreOpenStatus::kMovedAsideCorrupt) << r.message;
  EXPECT_THAT(r.message, HasSubstr("not an SQLite database"));
  EXPECT_THAT(r.message, HasSubstr("moved it aside to " + r.moved_to));
  EXPECT_THAT(r.moved_to, HasSubstr(db() + ".corrupt-"));
  EXPECT_EQ(ReadFile(r.moved_to), garbage);  // untouched
  // The store now works on a fresh, empty file.
  StoredAtlas atlas;
  std::string error;
  ASSERT_TRUE(store.Load(&atlas, &error)) << error;
  EXPECT_TRUE(atlas.frames.empty());
  AtlasSnapshot b;
  b.frames = {{0, Blob(0, 0), 0}};
  EXPECT_TRUE(store.Save(b, &error)) << error;
}

TEST_F(StoreDir, DamagedPagesAreRefusedAndMovedAside) {
  {
    AtlasStore store;
    ASSERT_TRUE(store.Open(dir_.string()).ok());
    AtlasSnapshot b;
    for (int i = 0; i < 200; ++i) b.frames.push_back({i, Blob(i, 0), 0});
    std::string error;
    ASSERT_TRUE(store.Save(b, &error)) << error;
  }  // closing checkpoints the WAL into the main file
  std::string bytes = ReadFile(db());
  ASSERT_GT(bytes.size(), 16u * 4096);
  for (size_t i = 2 * 4096; i < 12 * 4096; i += 4096) bytes.replace(i, 64, 64, '\x5a');
  std::ofstream(db(), std::ios::binary | std::ios::trunc) << bytes;

  AtlasStore store;
  const StoreOpenResult r = store.Open(dir_.string());
  ASSERT_EQ(r.status, StoreOpenStatus::kMovedAsideCorrupt) << r.message;
  EXPECT_THAT(r.message, HasSubstr("refused the atlas store"));
  EXPECT_EQ(ReadFile(r.moved_to), bytes);
}

TEST_F(StoreDir, NewerVersionIsRefusedAndMovedAside) {
  {
    AtlasStore store;
    ASSERT_TRUE(store.Open(dir_.string()).ok());
    AtlasSnapshot b;
    b.frames = {{7, Blob(7, 0), 0}};
    std::string error;
    ASSERT_TRUE(store.Save(b, &error));
  }
  SetSchemaVersion(db(), AtlasStore::kSchemaVersion + 1);
  AtlasStore store;
  const StoreOpenResult r = store.Open(dir_.string());
  ASSERT_EQ(r.status, StoreOpenStatus::kMovedAsideNewer) << r.message;
  EXPECT_THAT(r.message, HasSubstr("written by a newer atlasd (schema version " +
                                   std::to_string(AtlasStore::kSchemaVersion + 1)));
  EXPECT_THAT(r.moved_to, HasSubstr(".newer-"));
  StoredAtlas atlas;
  std::string error;
  ASSERT_TRUE(store.Load(&atlas, &error));
  EXPECT_TRUE(atlas.frames.empty());
  // The refused file still holds its atlas.
  sqlite3* raw = nullptr;
  ASSERT_EQ(sqlite3_open(r.moved_to.c_str(), &raw), SQLITE_OK);
  sqlite3_stmt* st = nullptr;
  ASSERT_EQ(sqlite3_prepare_v2(raw, "SELECT id FROM frames", -1, &st, nullptr), SQLITE_OK);
  ASSERT_EQ(sqlite3_step(st), SQLITE_ROW);
  EXPECT_EQ(sqlite3_column_int(st, 0), 7);
  sqlite3_finalize(st);
  sqlite3_close(raw);
}

TEST_F(StoreDir, ForeignDatabaseIsRefused) {
  fs::create_directories(dir_);
  sqlite3* raw = nullptr;
  ASSERT_EQ(sqlite3_open(db().c_str(), &raw), SQLITE_OK);
  ASSERT_EQ(sqlite3_exec(raw, "CREATE TABLE t (a)", nullptr, nullptr, nullptr), SQLITE_OK);
  sqlite3_close(raw);
  AtlasStore store;
  const StoreOpenResult r = store.Open(dir_.string());
  EXPECT_EQ(r.status, StoreOpenStatus::kMovedAsideCorrupt);
  EXPECT_THAT(r.message, HasSubstr("not an atlasd store"));
}

TEST_F(StoreDir, InterruptedCreationIsCreatedAgain) {
  fs::create_directories(dir_);
  sqlite3* raw = nullptr;
  ASSERT_EQ(sqlite3_open(db().c_str(), &raw), SQLITE_OK);
  ASSERT_EQ(sqlite3_exec(raw, "PRAGMA journal_mode=WAL", nullptr, nullptr, nullptr), SQLITE_OK);
  sqlite3_close(raw);
  ASSERT_GT(fs::file_size(db()), 0u);
  AtlasStore store;
  const StoreOpenResult r = store.Open(dir_.string());
  EXPECT_EQ(r.status, StoreOpenStatus::kCreated) << r.message;
  std::string error;
  EXPECT_TRUE(store.Save(Batch(1), &error)) << error;
}

void StoreDir::SaveFiveBatchesThenSigkill() {
  const pid_t child = fork();
  ASSERT_GE(child, 0);
  if (child == 0) {
    AtlasStore store;
    std::string error;
    if (!store.Open(dir_.string()).ok()) _exit(2);
    for (int k = 1; k <= 5; ++k) {
      if (!store.Save(Batch(k), &error)) _exit(3);
    }
    raise(SIGKILL);
  }
  int status = 0;
  ASSERT_EQ(waitpid(child, &status, 0), child);
  ASSERT_TRUE(WIFSIGNALED(status));
}

// A writer killed right after a commit leaves its -wal (and -shm) behind. Here the wal-index is
// also damaged, as a writer killed while updating it leaves it, so that a read-only connection
// cannot read the WAL without recovery: the store must recover it, not refuse it.
TEST_F(StoreDir, WalLeftByAKilledWriterIsRecoveredNotRefused) {
  ASSERT_NO_FATAL_FAILURE(SaveFiveBatchesThenSigkill());
  ASSERT_TRUE(fs::exists(db() + "-wal"));
  ASSERT_GT(fs::file_size(db() + "-wal"), 0u);
  {  // Make the two copies of the wal-index header disagree: the index needs recovery.
    ASSERT_TRUE(fs::exists(db() + "-shm"));
    std::fstream shm(db() + "-shm", std::ios::in | std::ios::out | std::ios::binary);
    shm.seekp(8);
    shm.write("\xde\xad\xbe\xef", 4);
  }

  AtlasStore store;
  const StoreOpenResult r = store.Open(dir_.string());
  ASSERT_EQ(r.status, StoreOpenStatus::kOpened) << r.message;
  StoredAtlas a;
  std::string error;
  ASSERT_TRUE(store.Load(&a, &error)) << error;
  ExpectConsistentPrefix(a, 5);
}

// kill -9 before the first checkpoint can leave the main file empty beside a full -wal. SQLite
// would open that as a new database and delete the log: the pair must be moved aside instead.
TEST_F(StoreDir, EmptyMainFileBesideAFullWalIsMovedAsideNotDiscarded) {
  ASSERT_NO_FATAL_FAILURE(SaveFiveBatchesThenSigkill());
  fs::resize_file(db(), 0);
  const std::string wal = ReadFile(db() + "-wal");
  ASSERT_FALSE(wal.empty());

  AtlasStore store;
  const StoreOpenResult r = store.Open(dir_.string());
  ASSERT_EQ(r.status, StoreOpenStatus::kMovedAsideCorrupt) << r.message;
  EXPECT_NE(r.message.find("write-ahead log"), std::string::npos) << r.message;
  EXPECT_EQ(ReadFile(r.moved_to + "-wal"), wal);
  StoredAtlas a;
  std::string error;
  ASSERT_TRUE(store.Load(&a, &error)) << error;
  EXPECT_TRUE(a.frames.empty());
}

TEST_F(StoreDir, UnusableDirectoryFailsWithAMessage) {
  fs::create_directories(dir_);
  std::ofstream(dir_ / "file") << "x";
  AtlasStore store;
  const StoreOpenResult r = store.Open((dir_ / "file" / "sub").string());
  EXPECT_EQ(r.status, StoreOpenStatus::kFailed);
  EXPECT_THAT(r.message, HasSubstr("cannot create the state directory"));
  EXPECT_FALSE(store.is_open());
}

// Saves a few frames and closes the store (which checkpoints the WAL into the main file).
void SaveFrames(const std::string& dir, int n) {
  AtlasStore store;
  ASSERT_TRUE(store.Open(dir).ok());
  AtlasSnapshot b;
  for (int i = 0; i < n; ++i) b.frames.push_back({i, Blob(i, 0), 0});
  std::string error;
  ASSERT_TRUE(store.Save(b, &error)) << error;
}

// The names in dir, sorted: what was created, moved or left.
std::vector<std::string> Names(const fs::path& dir) {
  std::vector<std::string> names;
  for (const auto& e : fs::directory_iterator(dir)) names.push_back(e.path().filename().string());
  std::sort(names.begin(), names.end());
  return names;
}

// What an Open() run in a child process returned. The child runs as nobody when the tests run
// as root (root reads files whatever their mode), so that permission problems are real.
struct ChildResult {
  std::string skip;  // non-empty: the child could not set itself up
  StoreOpenStatus status = StoreOpenStatus::kFailed;
  std::string message;
};

ChildResult OpenInUnprivilegedChild(const fs::path& reach,
                                    const std::function<StoreOpenResult(AtlasStore&)>& open) {
  ChildResult out;
  int fds[2];
  if (pipe(fds) != 0) {
    ADD_FAILURE() << "pipe failed";
    return out;
  }
  const pid_t child = fork();
  if (child == 0) {
    close(fds[0]);
    std::string reply;
    if (geteuid() == 0 &&
        (setgroups(0, nullptr) != 0 || setgid(65534) != 0 || setuid(65534) != 0)) {
      reply = "Scannot become uid 65534";
    } else if (access(reach.c_str(), X_OK) != 0) {
      reply = "S" + std::to_string(geteuid()) + " cannot search " + reach.string();
    } else {
      try {
        AtlasStore store;
        const StoreOpenResult r = open(store);
        reply = "R" + std::to_string(static_cast<int>(r.status)) + r.message;
      } catch (const std::exception& e) {
        reply = std::string("Ethrew ") + e.what();
      }
    }
    const bool written = write(fds[1], reply.data(), reply.size()) == ssize_t(reply.size());
    _exit(written ? 0 : 1);
  }
  close(fds[1]);
  if (child < 0) {
    close(fds[0]);
    ADD_FAILURE() << "fork failed";
    return out;
  }
  std::string reply;
  char buf[4096];
  ssize_t n;
  while ((n = read(fds[0], buf, sizeof(buf))) > 0) reply.append(buf, n);
  close(fds[0]);
  int status = 0;
  EXPECT_EQ(waitpid(child, &status, 0), child);
  EXPECT_TRUE(WIFEXITED(status) && WEXITSTATUS(status) == 0)
      << "the child died (signal " << (WIFSIGNALED(status) ? WTERMSIG(status) : 0) << ")";
  if (reply.empty()) {
    ADD_FAILURE() << "no reply from the child";
  } else if (reply[0] == 'S') {
    out.skip = reply.substr(1);
  } else if (reply[0] == 'E') {
    ADD_FAILURE() << "Open() " << reply.substr(1);
  } else {
    out.status = static_cast<StoreOpenStatus>(reply[1] - '0');
    out.message = reply.substr(2);
  }
  return out;
}

// Defect of the audit: a healthy store that could not be opened was taken for corrupt and
// moved aside. Now only a verdict on the file itself moves it.
TEST_F(StoreDir, UnreadableFileIsReportedNotMovedAside) {
  SaveFrames(dir_.string(), 3);
  const std::string bytes = ReadFile(db());
  const std::vector<std::string> before = Names(dir_);
  fs::permissions(db(), fs::perms::none);
  const ChildResult r =
      OpenInUnprivilegedChild(dir_, [&](AtlasStore& s) { return s.Open(dir_.string()); });
  fs::permissions(db(), fs::perms::owner_read | fs::perms::owner_write);
  if (!r.skip.empty()) GTEST_SKIP() << r.skip;
  EXPECT_EQ(r.status, StoreOpenStatus::kFailed) << r.message;
  EXPECT_THAT(r.message, HasSubstr("cannot read the atlas store " + db()));
  EXPECT_THAT(r.message, HasSubstr("Permission denied"));
  EXPECT_THAT(r.message, HasSubstr("check the owner and mode of " + db()));
  EXPECT_THAT(r.message, HasSubstr("nothing moved or changed"));
  EXPECT_EQ(Names(dir_), before);
  EXPECT_TRUE(ReadFile(db()) == bytes) << "the store file changed";
  AtlasStore store;  // the owner can still open it, whole
  ASSERT_EQ(store.Open(dir_.string()).status, StoreOpenStatus::kOpened);
  StoredAtlas a;
  std::string error;
  ASSERT_TRUE(store.Load(&a, &error)) << error;
  EXPECT_EQ(a.frames.size(), 3u);
}

// The same as root too: another process holds the store locked (SQLITE_BUSY).
TEST_F(StoreDir, LockedStoreIsReportedNotMovedAside) {
  SaveFrames(dir_.string(), 3);
  const std::string bytes = ReadFile(db());
  sqlite3* holder = nullptr;
  ASSERT_EQ(sqlite3_open(db().c_str(), &holder), SQLITE_OK);
  ASSERT_EQ(sqlite3_exec(holder, "PRAGMA locking_mode=EXCLUSIVE; BEGIN EXCLUSIVE;", nullptr,
                         nullptr, nullptr),
            SQLITE_OK);
  const std::vector<std::string> before = Names(dir_);
  {
    AtlasStore store;
    const StoreOpenResult r = store.Open(dir_.string());
    EXPECT_EQ(r.status, StoreOpenStatus::kFailed) << r.message;
    EXPECT_FALSE(store.is_open());
    EXPECT_TRUE(r.moved_to.empty());
    EXPECT_THAT(r.message, HasSubstr("cannot read the atlas store " + db()));
    EXPECT_THAT(r.message, HasSubstr("database is locked"));
    EXPECT_THAT(r.message, HasSubstr("another process holds the store locked"));
    EXPECT_EQ(Names(dir_), before);
  }
  ASSERT_EQ(sqlite3_exec(holder, "COMMIT", nullptr, nullptr, nullptr), SQLITE_OK);
  sqlite3_close(holder);
  EXPECT_TRUE(ReadFile(db()) == bytes) << "the store file changed";
  AtlasStore store;
  ASSERT_EQ(store.Open(dir_.string()).status, StoreOpenStatus::kOpened);
  StoredAtlas a;
  std::string error;
  ASSERT_TRUE(store.Load(&a, &error)) << error;
  EXPECT_EQ(a.frames.size(), 3u);
}

TEST_F(StoreDir, DirectoryInPlaceOfTheFileIsReportedNotMovedAside) {
  fs::create_directories(dir_ / AtlasStore::kFileName);
  std::ofstream(dir_ / AtlasStore::kFileName / "keep") << "x";
  AtlasStore store;
  const StoreOpenResult r = store.Open(dir_.string());
  EXPECT_EQ(r.status, StoreOpenStatus::kFailed) << r.message;
  EXPECT_THAT(r.message, HasSubstr(db() + " is not a regular file"));
  EXPECT_EQ(Names(dir_), std::vector<std::string>{AtlasStore::kFileName});
  EXPECT_EQ(ReadFile((dir_ / AtlasStore::kFileName / "keep").string()), "x");
}

// Defect of the audit: std::filesystem's throwing calls aborted the daemon ("terminate called
// ... Permission denied") on a state directory it cannot search.
TEST_F(StoreDir, UnsearchableDirectoryIsAnErrorNotAnException) {
  SaveFrames(dir_.string(), 2);
  const std::string bytes = ReadFile(db());
  fs::permissions(dir_, fs::perms::owner_read | fs::perms::owner_write);  // no search (x)
  const ChildResult r = OpenInUnprivilegedChild(
      dir_.parent_path(), [&](AtlasStore& s) { return s.Open(dir_.string()); });
  const ChildResult ro = OpenInUnprivilegedChild(
      dir_.parent_path(), [&](AtlasStore& s) { return s.OpenReadOnly(dir_.string()); });
  fs::permissions(dir_, fs::perms::owner_all);
  if (!r.skip.empty()) GTEST_SKIP() << r.skip;
  EXPECT_EQ(r.status, StoreOpenStatus::kFailed) << r.message;
  EXPECT_THAT(r.message, HasSubstr("cannot access state.directory " + dir_.string() +
                                   ": Permission denied; check the owner and mode of"));
  EXPECT_EQ(ro.status, StoreOpenStatus::kFailed) << ro.message;
  EXPECT_THAT(ro.message, HasSubstr("Permission denied"));
  EXPECT_EQ(Names(dir_), std::vector<std::string>{AtlasStore::kFileName});
  EXPECT_TRUE(ReadFile(db()) == bytes) << "the store file changed";
}

TEST_F(StoreDir, ReadOnlyOpenReadsAndCreatesNothing) {
  SaveFrames(dir_.string(), 4);
  const std::vector<std::string> before = Names(dir_);
  ASSERT_EQ(before, std::vector<std::string>{AtlasStore::kFileName});
  const std::string bytes = ReadFile(db());
  {
    AtlasStore store;
    const StoreOpenResult r = store.OpenReadOnly(dir_.string());
    ASSERT_EQ(r.status, StoreOpenStatus::kOpened) << r.message;
    StoredAtlas a;
    std::string error;
    ASSERT_TRUE(store.Load(&a, &error)) << error;
    EXPECT_EQ(a.frames.size(), 4u);
    EXPECT_FALSE(store.Save(Batch(1), &error));
    EXPECT_THAT(error, HasSubstr("read-only"));
    EXPECT_EQ(Names(dir_), before);  // no -wal, no -shm
  }
  EXPECT_EQ(Names(dir_), before);
  EXPECT_TRUE(ReadFile(db()) == bytes) << "the store file changed";
}

// A store in use (or left by a killed writer) keeps its last commits in the -wal file: the
// read-only open reads them, and creates nothing.
TEST_F(StoreDir, ReadOnlyOpenReadsTheWriteAheadLogOfAStoreInUse) {
  AtlasStore writer;
  ASSERT_TRUE(writer.Open(dir_.string()).ok());
  std::string error;
  for (int k = 1; k <= 3; ++k) ASSERT_TRUE(writer.Save(Batch(k), &error)) << error;
  const std::vector<std::string> before = Names(dir_);
  ASSERT_EQ(before.size(), 3u);  // the file, -shm, -wal
  AtlasStore reader;
  const StoreOpenResult r = reader.OpenReadOnly(dir_.string());
  ASSERT_EQ(r.status, StoreOpenStatus::kOpened) << r.message;
  StoredAtlas a;
  ASSERT_TRUE(reader.Load(&a, &error)) << error;
  ExpectConsistentPrefix(a, 3);
  EXPECT_EQ(Names(dir_), before);
}

TEST_F(StoreDir, ReadOnlyOpenOfNoStoreCreatesNothing) {
  AtlasStore store;
  StoreOpenResult r = store.OpenReadOnly(dir_.string());
  EXPECT_EQ(r.status, StoreOpenStatus::kFailed);
  EXPECT_THAT(r.message, HasSubstr("there is no saved atlas: the state directory"));
  EXPECT_FALSE(fs::exists(dir_));
  fs::create_directories(dir_);
  r = store.OpenReadOnly(dir_.string());
  EXPECT_EQ(r.status, StoreOpenStatus::kFailed);
  EXPECT_THAT(r.message, HasSubstr("there is no saved atlas: " + db() + " does not exist"));
  EXPECT_TRUE(fs::is_empty(dir_));
  EXPECT_FALSE(store.is_open());
}

TEST_F(StoreDir, ReadOnlyOpenOfACorruptStoreMovesNothing) {
  fs::create_directories(dir_);
  const std::string garbage(5000, 'x');
  std::ofstream(db(), std::ios::binary) << garbage;
  AtlasStore store;
  const StoreOpenResult r = store.OpenReadOnly(dir_.string());
  EXPECT_EQ(r.status, StoreOpenStatus::kFailed);
  EXPECT_THAT(r.message, HasSubstr("SQLite finds it corrupt"));
  EXPECT_EQ(Names(dir_), std::vector<std::string>{AtlasStore::kFileName});
  EXPECT_TRUE(ReadFile(db()) == garbage) << "the store file changed";
}

// Logical batch k (1, 2, ...) adds frame k, edge (k-1, k) and rewrites frame 0 and
// metadata "last" to k. A consistent store after any crash holds exactly batches 1..last.
AtlasSnapshot Batch(int k) {
  AtlasSnapshot b;
  b.frames = {{k, Blob(k, 0), 0}, {0, Blob(0, k), 0}};
  b.edges = {Edge(k - 1, k, k)};
  b.metadata["last"] = std::to_string(k);
  return b;
}

void ExpectConsistentPrefix(const StoredAtlas& a, int last) {
  if (last == 0) {  // nothing committed yet
    EXPECT_TRUE(a.frames.empty());
    EXPECT_TRUE(a.edges.empty());
    return;
  }
  ASSERT_EQ(a.frames.size(), static_cast<size_t>(last + 1));
  EXPECT_EQ(a.frames[0].blob, Blob(0, last));
  for (int k = 1; k <= last; ++k) {
    ASSERT_EQ(a.frames[k].id, k);
    ASSERT_EQ(a.frames[k].blob, Blob(k, 0)) << "frame " << k;
  }
  ASSERT_EQ(a.edges.size(), static_cast<size_t>(last));
  for (int k = 1; k <= last; ++k) {
    ASSERT_EQ(a.edges[k - 1].frame_to, k);
    ASSERT_EQ(a.edges[k - 1].covariance, Edge(k - 1, k, k).covariance);
  }
}

// Writes logical batches forever, directly or through the writer thread; writes "r" to
// ready_fd once the store is open and, writing directly, "w" once kReportAfter batches are
// committed; never returns.
constexpr int kReportAfter = 25;
[[noreturn]] void WriteUntilKilled(const std::string& dir, bool through_writer, int ready_fd) {
  AtlasStore store;
  if (!store.Open(dir).ok()) _exit(2);
  StoredAtlas a;
  std::string error;
  if (!store.Load(&a, &error)) _exit(3);
  int k = a.metadata.count("last") ? std::stoi(a.metadata["last"]) : 0;
  if (write(ready_fd, "r", 1) != 1) _exit(5);
  if (through_writer) {
    AtlasStoreWriter writer(&store, 4);
    writer.Start();
    while (true) {
      writer.Submit(Batch(++k));
      std::this_thread::sleep_for(std::chrono::microseconds(200));
    }
  }
  int saved = 0;
  while (true) {
    if (!store.Save(Batch(++k), &error)) _exit(4);
    if (++saved == kReportAfter && write(ready_fd, "w", 1) != 1) _exit(5);
  }
}

// Even rounds kill at a random moment after fork (opening and creating included); odd rounds at
// a random moment after the child has started writing, half of those through the writer thread.
// A last round kills only after the child has said it committed kReportAfter batches, so the
// test has something to lose however slow the machine is.
TEST_F(StoreDir, SigkillAtRandomMomentsLeavesAConsistentPrefix) {
  std::mt19937 rng(20261122);
  std::uniform_int_distribution<int> delay_ms(0, 60);
  int last = 0;
  for (int round = 0; round <= 16; ++round) {
    const bool final_round = round == 16;
    int ready[2];
    ASSERT_EQ(pipe(ready), 0);
    const pid_t child = fork();
    ASSERT_GE(child, 0);
    if (child == 0) {
      close(ready[0]);
      WriteUntilKilled(dir_.string(), round % 4 == 3, ready[1]);
    }
    close(ready[1]);
    if (round % 2 == 1 || final_round) {
      char byte;
      ASSERT_EQ(read(ready[0], &byte, 1), 1) << "the child could not open the store";
    }
    const int before = last;
    if (final_round) {
      char byte = 0;
      ASSERT_EQ(read(ready[0], &byte, 1), 1) << "the child stopped writing";
      ASSERT_EQ(byte, 'w');
    } else {
      std::this_thread::sleep_for(std::chrono::milliseconds(delay_ms(rng)));
    }
    ASSERT_EQ(kill(child, SIGKILL), 0);
    close(ready[0]);
    int status = 0;
    ASSERT_EQ(waitpid(child, &status, 0), child);
    ASSERT_TRUE(WIFSIGNALED(status))
        << "the writer exited by itself with status " << WEXITSTATUS(status);

    AtlasStore store;
    const StoreOpenResult r = store.Open(dir_.string());
    // Open() ran integrity_check; kCreated only if the child was killed before it wrote.
    ASSERT_TRUE(r.status == StoreOpenStatus::kOpened || r.status == StoreOpenStatus::kCreated)
        << r.message;
    StoredAtlas a;
    std::string error;
    ASSERT_TRUE(store.Load(&a, &error)) << error;
    const int now = a.metadata.count("last") ? std::stoi(a.metadata["last"]) : 0;
    EXPECT_GE(now, last) << "a committed batch was lost";
    if (final_round) {
      EXPECT_GE(now, before + kReportAfter) << "a committed batch was lost";
    }
    last = now;
    ExpectConsistentPrefix(a, last);
  }
  RecordProperty("batches_committed", last);
}

TEST_F(StoreDir, WriterSavesInOrderAndMergesWhenFull) {
  AtlasStore store;
  ASSERT_TRUE(store.Open(dir_.string()).ok());
  {
    AtlasStoreWriter writer(&store, 3);
    // Not started yet: the queue fills up, and the two oldest batches are merged.
    int coalesced = 0;
    for (int k = 1; k <= 6; ++k) {
      coalesced += writer.Submit(Batch(k)) == SubmitResult::kCoalesced;
    }
    EXPECT_EQ(coalesced, 3);
    StoreWriterStats s = writer.Stats();
    EXPECT_EQ(s.queued, 3u);
    EXPECT_EQ(s.coalesced, 3u);
    writer.Start();
    ASSERT_TRUE(writer.Flush(std::chrono::seconds(10)));
    s = writer.Stats();
    EXPECT_EQ(s.saved, 3u);
    EXPECT_EQ(s.errors, 0u);
    EXPECT_EQ(writer.Submit(Batch(7)), SubmitResult::kQueued);
  }  // the destructor writes batch 7 before joining
  StoredAtlas a;
  std::string error;
  ASSERT_TRUE(store.Load(&a, &error)) << error;
  ExpectConsistentPrefix(a, 7);
  EXPECT_EQ(a.metadata["batch_sequence"], "4");
}

TEST_F(StoreDir, WriterKeepsAFailedBatchAndCountsTheError) {
  AtlasStore closed;  // never opened: every save fails
  // A retry interval of an hour: a Stop() that waited it out would hang the test until ctest's
  // timeout, so returning at all is the check.
  AtlasStoreWriter writer(&closed, 2, std::chrono::hours(1));
  writer.Start();
  writer.Submit(Batch(1));
  for (int i = 0; i < 500 && writer.Stats().errors == 0; ++i) {
    std::this_thread::sleep_for(std::chrono::milliseconds(2));
  }
  const StoreWriterStats s = writer.Stats();
  EXPECT_EQ(s.errors, 1u);
  EXPECT_EQ(s.saved, 0u);
  EXPECT_EQ(s.queued, 1u);  // kept for a retry
  EXPECT_THAT(s.last_error, HasSubstr("not open"));
  writer.Stop();  // does not wait out the retry interval
  EXPECT_EQ(writer.Submit(Batch(2)), SubmitResult::kStopped);
}

// A batch that failed is never left out while a later one is saved, not even when the writer
// stops: the later batch's rows could depend on it (a frame row written once, an image that
// needs it). Batch 2 cannot be saved (an edge with NaN, which SQLite stores as NULL).
TEST_F(StoreDir, WriterNeverSavesABatchWithoutTheOnesBefore) {
  AtlasStore store;
  ASSERT_TRUE(store.Open(dir_.string()).ok());
  {
    AtlasStoreWriter writer(&store, 4, std::chrono::hours(1));
    writer.Start();
    writer.Submit(Batch(1));
    ASSERT_TRUE(writer.Flush(std::chrono::seconds(10)));
    AtlasSnapshot bad = Batch(2);
    bad.edges[0].x = std::numeric_limits<double>::quiet_NaN();
    writer.Submit(std::move(bad));
    for (int i = 0; i < 500 && writer.Stats().errors == 0; ++i)
      std::this_thread::sleep_for(std::chrono::milliseconds(2));
    ASSERT_EQ(writer.Stats().errors, 1u);
    writer.Submit(Batch(3));
    // Stopping: batch 2 fails again, then with batch 3 merged into it; both are dropped.
    writer.Stop();
    EXPECT_EQ(writer.Stats().errors, 3u);
    EXPECT_EQ(writer.Stats().saved, 1u);
  }
  StoredAtlas a;
  std::string error;
  ASSERT_TRUE(store.Load(&a, &error)) << error;
  ExpectConsistentPrefix(a, 1);
  EXPECT_EQ(a.metadata["last"], "1");
}

TEST(AtlasSnapshot, MergeLaterReplacesByKey) {
  AtlasSnapshot a = Batch(1);
  a.MergeLater(Batch(2));
  ASSERT_EQ(a.frames.size(), 3u);  // frames 1, 0 (version 2), 2
  EXPECT_EQ(a.frames[1].blob, Blob(0, 2));
  EXPECT_EQ(a.edges.size(), 2u);
  EXPECT_EQ(a.metadata["last"], "2");
}

}  // namespace
}  // namespace atlas
