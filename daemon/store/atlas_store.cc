#include "daemon/store/atlas_store.h"

#include <sqlite3.h>

#include <bit>
#include <chrono>
#include <cstring>
#include <ctime>
#include <filesystem>

namespace atlas {
namespace {

static_assert(std::endian::native == std::endian::little,
              "edge covariances are stored as little-endian doubles");

namespace fs = std::filesystem;

int64_t UnixMicros() {
  return std::chrono::duration_cast<std::chrono::microseconds>(
             std::chrono::system_clock::now().time_since_epoch())
      .count();
}

std::string UtcStamp() {
  const std::time_t t = std::time(nullptr);
  std::tm tm{};
  gmtime_r(&t, &tm);
  char buf[32];
  std::strftime(buf, sizeof(buf), "%Y%m%dT%H%M%SZ", &tm);
  return buf;
}

// Renames path (and its -wal, -shm companions) to path.<kind>-<UTC stamp>[-n]; never replaces
// an existing file.
bool MoveAside(const std::string& path, const char* kind, std::string* moved_to,
               std::string* error) {
  const std::string base = path + "." + kind + "-" + UtcStamp();
  std::string target = base;
  for (int n = 2; fs::exists(target) || fs::exists(target + "-wal"); ++n) {
    target = base + "-" + std::to_string(n);
  }
  std::error_code ec;
  fs::rename(path, target, ec);
  if (ec) {
    *error = "cannot rename " + path + " to " + target + ": " + ec.message();
    return false;
  }
  for (const char* suffix : {"-wal", "-shm"}) {
    if (fs::exists(path + suffix)) fs::rename(path + suffix, target + suffix, ec);
  }
  *moved_to = target;
  return true;
}

std::string ErrorText(sqlite3* db) {
  if (db == nullptr) return "out of memory";
  return std::string(sqlite3_errmsg(db)) + ", SQLite code " +
         std::to_string(sqlite3_extended_errcode(db));
}

constexpr const char* kSchema = R"sql(
CREATE TABLE IF NOT EXISTS schema_version (version INTEGER NOT NULL);
CREATE TABLE IF NOT EXISTS metadata (key TEXT PRIMARY KEY, value TEXT NOT NULL);
CREATE TABLE IF NOT EXISTS frames (
  id INTEGER PRIMARY KEY,
  blob BLOB NOT NULL,
  updated_at INTEGER NOT NULL);
CREATE TABLE IF NOT EXISTS edges (
  frame_from INTEGER NOT NULL,
  frame_to INTEGER NOT NULL,
  x REAL NOT NULL,
  y REAL NOT NULL,
  theta REAL NOT NULL,
  covariance BLOB NOT NULL,
  kind INTEGER NOT NULL,
  updated_at INTEGER NOT NULL,
  PRIMARY KEY (frame_from, frame_to));
)sql";

}  // namespace

const char* ToString(StoreOpenStatus s) {
  switch (s) {
    case StoreOpenStatus::kOpened:
      return "opened";
    case StoreOpenStatus::kCreated:
      return "created";
    case StoreOpenStatus::kMovedAsideCorrupt:
      return "moved aside (corrupt)";
    case StoreOpenStatus::kMovedAsideNewer:
      return "moved aside (newer version)";
    case StoreOpenStatus::kFailed:
      return "failed";
  }
  return "?";
}

void AtlasSnapshot::MergeLater(AtlasSnapshot&& later) {
  for (StoredFrame& f : later.frames) {
    bool replaced = false;
    for (StoredFrame& mine : frames) {
      if (mine.id == f.id) {
        mine = std::move(f);
        replaced = true;
        break;
      }
    }
    if (!replaced) frames.push_back(std::move(f));
  }
  for (StoredEdge& e : later.edges) {
    bool replaced = false;
    for (StoredEdge& mine : edges) {
      if (mine.frame_from == e.frame_from && mine.frame_to == e.frame_to) {
        mine = e;
        replaced = true;
        break;
      }
    }
    if (!replaced) edges.push_back(e);
  }
  for (auto& [k, v] : later.metadata) metadata[k] = std::move(v);
  later = AtlasSnapshot{};
}

AtlasStore::~AtlasStore() { Close(); }

void AtlasStore::FinalizeStatements() {
  for (sqlite3_stmt** s : {&upsert_frame_, &upsert_edge_, &upsert_metadata_, &bump_sequence_}) {
    sqlite3_finalize(*s);
    *s = nullptr;
  }
}

void AtlasStore::Close() {
  FinalizeStatements();
  if (db_ != nullptr) sqlite3_close(db_);
  db_ = nullptr;
}

bool AtlasStore::Exec(const char* sql, std::string* error) {
  char* msg = nullptr;
  if (sqlite3_exec(db_, sql, nullptr, nullptr, &msg) == SQLITE_OK) return true;
  *error = msg != nullptr ? msg : ErrorText(db_);
  sqlite3_free(msg);
  return false;
}

// Checks on a read-only connection, so that checking never writes to the file. A WAL file left
// by a killed process may need recovery, which a read-only connection cannot do (SQLITE_READONLY
// and its extended codes): then the check runs on a read-write connection that recovers the WAL
// index, but does not checkpoint into the main file when it closes.
AtlasStore::Check AtlasStore::CheckExisting(std::string* why, int* found_version) {
  Check verdict = Check::kOurs;
  for (const bool read_only : {true, false}) {
    sqlite3* db = nullptr;
    int rc = sqlite3_open_v2(path_.c_str(), &db,
                             read_only ? SQLITE_OPEN_READONLY : SQLITE_OPEN_READWRITE, nullptr);
    if (rc == SQLITE_OK) {
      sqlite3_busy_timeout(db, 2000);
      if (!read_only) sqlite3_db_config(db, SQLITE_DBCONFIG_NO_CKPT_ON_CLOSE, 1, nullptr);
      rc = CheckConnection(db, why, found_version, &verdict);
    }
    const std::string error = ErrorText(db);
    sqlite3_close(db);
    if (read_only && (rc & 0xff) == SQLITE_READONLY) continue;  // needs recovery: retry writable
    if (rc != SQLITE_OK && verdict == Check::kOurs) {
      *why = rc == SQLITE_NOTADB ? "it is not an SQLite database"
                                 : "SQLite cannot read it (" + error + ")";
      verdict = Check::kNotOurs;
    }
    break;
  }
  return verdict;
}

// Runs integrity_check and reads schema_version; returns the SQLite code of a failure to read,
// or SQLITE_OK with *verdict set.
int AtlasStore::CheckConnection(sqlite3* db, std::string* why, int* found_version, Check* verdict) {
  sqlite3_stmt* st = nullptr;
  int rc = sqlite3_prepare_v2(db, "PRAGMA integrity_check", -1, &st, nullptr);
  if (rc == SQLITE_OK) {
    rc = sqlite3_step(st);
    if (rc == SQLITE_ROW) {
      const char* first = reinterpret_cast<const char*>(sqlite3_column_text(st, 0));
      if (first == nullptr || std::strcmp(first, "ok") != 0) {
        *why = std::string("it fails PRAGMA integrity_check (") + (first ? first : "?") + ")";
        *verdict = Check::kNotOurs;
      }
      rc = SQLITE_OK;
    }
  }
  sqlite3_finalize(st);
  if (rc != SQLITE_OK || *verdict != Check::kOurs) return rc;

  // A database without any table is a store whose creation was interrupted (the schema is
  // created in one transaction, after the journal mode): it is simply created again.
  st = nullptr;
  rc = sqlite3_prepare_v2(db, "SELECT count(*) FROM sqlite_master", -1, &st, nullptr);
  if (rc == SQLITE_OK) rc = sqlite3_step(st) == SQLITE_ROW ? SQLITE_OK : sqlite3_errcode(db);
  const bool no_tables = rc == SQLITE_OK && sqlite3_column_int(st, 0) == 0;
  sqlite3_finalize(st);
  if (rc != SQLITE_OK) return rc;
  if (no_tables) {
    *verdict = Check::kEmpty;
    return SQLITE_OK;
  }

  st = nullptr;
  if (sqlite3_prepare_v2(db, "SELECT version FROM schema_version", -1, &st, nullptr) != SQLITE_OK ||
      sqlite3_step(st) != SQLITE_ROW) {
    *why = "it has no schema_version: it is not an atlasd store";
    *verdict = Check::kNotOurs;
  } else {
    *found_version = sqlite3_column_int(st, 0);
    if (*found_version > kSchemaVersion) {
      *why = "it was written by a newer atlasd (schema version " + std::to_string(*found_version) +
             "; this atlasd reads up to " + std::to_string(kSchemaVersion) + ")";
      *verdict = Check::kNewer;
    } else if (*found_version < 1) {
      *why = "its schema_version " + std::to_string(*found_version) + " is invalid";
      *verdict = Check::kNotOurs;
    }
  }
  sqlite3_finalize(st);
  return SQLITE_OK;
}

bool AtlasStore::Configure(std::string* error) {
  sqlite3_busy_timeout(db_, 2000);
  return Exec("PRAGMA journal_mode=WAL; PRAGMA synchronous=NORMAL;", error);
}

bool AtlasStore::CreateSchema(std::string* error) {
  if (!Exec("BEGIN IMMEDIATE", error)) return false;
  std::string ignored;
  if (!Exec(kSchema, error) ||
      !Exec(("INSERT INTO schema_version (version) SELECT " + std::to_string(kSchemaVersion) +
             " WHERE NOT EXISTS (SELECT 1 FROM schema_version)")
                .c_str(),
            error) ||
      !Exec("COMMIT", error)) {
    Exec("ROLLBACK", &ignored);
    return false;
  }
  return true;
}

bool AtlasStore::Prepare(std::string* error) {
  const std::pair<sqlite3_stmt**, const char*> statements[] = {
      {&upsert_frame_, "INSERT OR REPLACE INTO frames (id, blob, updated_at) VALUES (?, ?, ?)"},
      {&upsert_edge_,
       "INSERT OR REPLACE INTO edges (frame_from, frame_to, x, y, theta, covariance, kind, "
       "updated_at) VALUES (?, ?, ?, ?, ?, ?, ?, ?)"},
      {&upsert_metadata_, "INSERT OR REPLACE INTO metadata (key, value) VALUES (?, ?)"},
      {&bump_sequence_,
       "INSERT INTO metadata (key, value) VALUES ('batch_sequence', '1') ON CONFLICT (key) DO "
       "UPDATE SET value = CAST(value AS INTEGER) + 1"}};
  for (const auto& [stmt, sql] : statements) {
    if (sqlite3_prepare_v2(db_, sql, -1, stmt, nullptr) != SQLITE_OK) {
      *error = ErrorText(db_);
      return false;
    }
  }
  return true;
}

StoreOpenResult AtlasStore::Open(const std::string& directory) {
  Close();
  StoreOpenResult result;
  std::error_code ec;
  fs::create_directories(directory, ec);
  if (ec) {
    result.message = "cannot create the state directory " + directory + ": " + ec.message();
    return result;
  }
  path_ = (fs::path(directory) / kFileName).string();
  const bool existed = fs::exists(path_) && fs::file_size(path_, ec) > 0;

  result.status = existed ? StoreOpenStatus::kOpened : StoreOpenStatus::kCreated;
  if (existed) {
    std::string why;
    int version = 0;
    const Check check = CheckExisting(&why, &version);
    if (check == Check::kEmpty) result.status = StoreOpenStatus::kCreated;
    if (check == Check::kNotOurs || check == Check::kNewer) {
      const char* kind = check == Check::kNewer ? "newer" : "corrupt";
      std::string error;
      if (!MoveAside(path_, kind, &result.moved_to, &error)) {
        result.status = StoreOpenStatus::kFailed;
        result.message = "refused the atlas store " + path_ + " because " + why +
                         ", and could not move it aside: " + error;
        return result;
      }
      result.status = check == Check::kNewer ? StoreOpenStatus::kMovedAsideNewer
                                             : StoreOpenStatus::kMovedAsideCorrupt;
      result.message = "refused the atlas store " + path_ + " because " + why +
                       "; moved it aside to " + result.moved_to +
                       " (kept for inspection) and started an empty atlas";
    }
  }

  std::string error;
  if (sqlite3_open_v2(path_.c_str(), &db_, SQLITE_OPEN_READWRITE | SQLITE_OPEN_CREATE, nullptr) !=
          SQLITE_OK ||
      !Configure(&error) || !CreateSchema(&error) || !Prepare(&error)) {
    if (error.empty()) error = ErrorText(db_);
    Close();
    result.status = StoreOpenStatus::kFailed;
    result.message = "cannot open the atlas store " + path_ + ": " + error;
    return result;
  }
  if (result.status == StoreOpenStatus::kOpened) {
    result.message = "opened the atlas store " + path_;
  } else if (result.status == StoreOpenStatus::kCreated) {
    result.message = "created a new atlas store " + path_;
  }
  return result;
}

StoreOpenResult AtlasStore::RefuseAndStartEmpty(bool newer, const std::string& why) {
  StoreOpenResult result;
  if (db_ == nullptr) {
    result.message = "the atlas store is not open";
    return result;
  }
  const std::string directory = fs::path(path_).parent_path().string();
  Close();  // checkpoints the WAL into the file, so the file moved aside is whole
  std::string error, moved_to;
  if (!MoveAside(path_, newer ? "newer" : "corrupt", &moved_to, &error)) {
    result.message = "refused the atlas store " + path_ + " because " + why +
                     ", and could not move it aside: " + error;
    return result;
  }
  result = Open(directory);
  if (!result.ok()) return result;
  result.status = newer ? StoreOpenStatus::kMovedAsideNewer : StoreOpenStatus::kMovedAsideCorrupt;
  result.moved_to = moved_to;
  result.message = "refused the atlas store " + path_ + " because " + why + "; moved it aside to " +
                   moved_to + " (kept for inspection) and started an empty atlas";
  return result;
}

bool AtlasStore::Save(const AtlasSnapshot& batch, std::string* error) {
  error->clear();
  if (db_ == nullptr) {
    *error = "the atlas store is not open";
    return false;
  }
  if (!Exec("BEGIN IMMEDIATE", error)) return false;
  const int64_t now = UnixMicros();
  auto run = [&](sqlite3_stmt* st) {
    const bool good = sqlite3_step(st) == SQLITE_DONE;
    if (!good) *error = ErrorText(db_);
    sqlite3_reset(st);
    sqlite3_clear_bindings(st);
    return good;
  };
  bool good = true;
  for (const StoredFrame& f : batch.frames) {
    if (!good) break;
    sqlite3_bind_int(upsert_frame_, 1, f.id);
    sqlite3_bind_blob(upsert_frame_, 2, f.blob.data(), static_cast<int>(f.blob.size()),
                      SQLITE_STATIC);
    sqlite3_bind_int64(upsert_frame_, 3, now);
    good = run(upsert_frame_);
  }
  for (const StoredEdge& e : batch.edges) {
    if (!good) break;
    sqlite3_bind_int(upsert_edge_, 1, e.frame_from);
    sqlite3_bind_int(upsert_edge_, 2, e.frame_to);
    sqlite3_bind_double(upsert_edge_, 3, e.x);
    sqlite3_bind_double(upsert_edge_, 4, e.y);
    sqlite3_bind_double(upsert_edge_, 5, e.theta);
    sqlite3_bind_blob(upsert_edge_, 6, e.covariance.data(), sizeof(e.covariance), SQLITE_STATIC);
    sqlite3_bind_int(upsert_edge_, 7, e.kind);
    sqlite3_bind_int64(upsert_edge_, 8, now);
    good = run(upsert_edge_);
  }
  for (const auto& [key, value] : batch.metadata) {
    if (!good) break;
    sqlite3_bind_text(upsert_metadata_, 1, key.data(), static_cast<int>(key.size()), SQLITE_STATIC);
    // Values are byte strings (the atlas image is binary): stored as BLOBs, read by length.
    sqlite3_bind_blob(upsert_metadata_, 2, value.data(), static_cast<int>(value.size()),
                      SQLITE_STATIC);
    good = run(upsert_metadata_);
  }
  if (good) good = run(bump_sequence_);
  if (good && Exec("COMMIT", error)) return true;
  if (error->empty()) *error = ErrorText(db_);
  std::string ignored;
  Exec("ROLLBACK", &ignored);
  return false;
}

bool AtlasStore::Load(StoredAtlas* out, std::string* error) {
  *out = StoredAtlas{};
  if (db_ == nullptr) {
    *error = "the atlas store is not open";
    return false;
  }
  sqlite3_stmt* st = nullptr;
  auto fail = [&](const std::string& what) {
    *error = what.empty() ? ErrorText(db_) : what;
    sqlite3_finalize(st);
    return false;
  };
  if (sqlite3_prepare_v2(db_, "SELECT id, blob, updated_at FROM frames ORDER BY id", -1, &st,
                         nullptr) != SQLITE_OK) {
    return fail("");
  }
  int rc;
  while ((rc = sqlite3_step(st)) == SQLITE_ROW) {
    StoredFrame f;
    f.id = sqlite3_column_int(st, 0);
    const void* blob = sqlite3_column_blob(st, 1);
    f.blob.assign(static_cast<const char*>(blob), blob ? sqlite3_column_bytes(st, 1) : 0);
    f.updated_at = sqlite3_column_int64(st, 2);
    out->frames.push_back(std::move(f));
  }
  if (rc != SQLITE_DONE) return fail("");
  sqlite3_finalize(st);
  st = nullptr;

  if (sqlite3_prepare_v2(db_,
                         "SELECT frame_from, frame_to, x, y, theta, covariance, kind FROM edges "
                         "ORDER BY frame_from, frame_to",
                         -1, &st, nullptr) != SQLITE_OK) {
    return fail("");
  }
  while ((rc = sqlite3_step(st)) == SQLITE_ROW) {
    StoredEdge e;
    e.frame_from = sqlite3_column_int(st, 0);
    e.frame_to = sqlite3_column_int(st, 1);
    e.x = sqlite3_column_double(st, 2);
    e.y = sqlite3_column_double(st, 3);
    e.theta = sqlite3_column_double(st, 4);
    const void* cov = sqlite3_column_blob(st, 5);
    if (cov == nullptr || sqlite3_column_bytes(st, 5) != sizeof(e.covariance)) {
      return fail("edge " + std::to_string(e.frame_from) + "-" + std::to_string(e.frame_to) +
                  " has a covariance that is not 9 doubles");
    }
    std::memcpy(e.covariance.data(), cov, sizeof(e.covariance));
    e.kind = sqlite3_column_int(st, 6);
    out->edges.push_back(e);
  }
  if (rc != SQLITE_DONE) return fail("");
  sqlite3_finalize(st);
  st = nullptr;

  if (sqlite3_prepare_v2(db_, "SELECT key, value FROM metadata", -1, &st, nullptr) != SQLITE_OK) {
    return fail("");
  }
  while ((rc = sqlite3_step(st)) == SQLITE_ROW) {
    const char* k = reinterpret_cast<const char*>(sqlite3_column_text(st, 0));
    const int key_bytes = sqlite3_column_bytes(st, 0);
    const void* v = sqlite3_column_blob(st, 1);  // also for TEXT values (batch_sequence)
    const int value_bytes = sqlite3_column_bytes(st, 1);
    out->metadata[std::string(k ? k : "", k ? key_bytes : 0)] =
        std::string(static_cast<const char*>(v), v ? value_bytes : 0);
  }
  if (rc != SQLITE_DONE) return fail("");
  sqlite3_finalize(st);
  return true;
}

}  // namespace atlas
