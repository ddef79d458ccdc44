#include "daemon/store/atlas_store.h"

#include <pwd.h>
#include <sqlite3.h>
#include <unistd.h>

#include <bit>
#include <chrono>
#include <cstdint>
#include <cstring>
#include <ctime>
#include <filesystem>
#include <vector>

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

// Whether p exists; false with *error when that cannot be told (e.g. a directory on the way
// that cannot be searched).
bool Exists(const std::string& p, bool* exists, std::string* error) {
  std::error_code ec;
  const fs::file_status st = fs::status(p, ec);
  *exists = st.type() != fs::file_type::not_found;
  if (ec && *exists) {
    *error = "cannot access " + p + ": " + ec.message();
    return false;
  }
  return true;
}

// Renames path (and its -wal, -shm companions) to path.<kind>-<UTC stamp>[-n]; never replaces
// an existing file. When a companion cannot follow, what was renamed is renamed back, so that
// the file is never separated from its write-ahead log.
bool MoveAside(const std::string& path, const char* kind, std::string* moved_to,
               std::string* error) {
  const std::string base = path + "." + kind + "-" + UtcStamp();
  std::string target = base;
  for (int n = 2;; ++n) {
    bool taken = false, taken_wal = false;
    if (!Exists(target, &taken, error) || !Exists(target + "-wal", &taken_wal, error)) {
      return false;
    }
    if (!taken && !taken_wal) break;
    target = base + "-" + std::to_string(n);
  }
  std::error_code ec;
  fs::rename(path, target, ec);
  if (ec) {
    *error = "cannot rename " + path + " to " + target + ": " + ec.message();
    return false;
  }
  std::vector<std::string> moved = {""};
  for (const char* suffix : {"-wal", "-shm"}) {
    bool present = false;
    std::string why;
    if (Exists(path + suffix, &present, &why) && present) {
      fs::rename(path + suffix, target + suffix, ec);
      if (!ec) {
        moved.push_back(suffix);
        continue;
      }
      why = "cannot rename " + path + suffix + " to " + target + suffix + ": " + ec.message();
    }
    if (why.empty()) continue;
    for (const std::string& s : moved) fs::rename(target + s, path + s, ec);
    *error = why + " (the store was left where it was)";
    return false;
  }
  *moved_to = target;
  return true;
}

bool IsCorruption(int code) {
  return (code & 0xff) == SQLITE_CORRUPT || (code & 0xff) == SQLITE_NOTADB;
}

// The SQLite message and code of db's last error, with the system's error text when the
// operating system refused something.
std::string ErrorText(sqlite3* db) {
  if (db == nullptr) return "out of memory";
  const int code = sqlite3_extended_errcode(db);
  std::string text = std::string(sqlite3_errmsg(db)) + ", SQLite code " + std::to_string(code);
  const int primary = code & 0xff;
  const int sys = sqlite3_system_errno(db);
  if (sys != 0 && (primary == SQLITE_CANTOPEN || primary == SQLITE_IOERR ||
                   primary == SQLITE_PERM || primary == SQLITE_READONLY)) {
    text += ": " + std::string(std::strerror(sys));
  }
  return text;
}

std::string RunningAs() {
  const uid_t uid = geteuid();
  passwd pw{};
  passwd* found = nullptr;
  char buf[1024];
  if (getpwuid_r(uid, &pw, buf, sizeof(buf), &found) == 0 && found != nullptr) {
    return "user " + std::string(found->pw_name) + " (uid " + std::to_string(uid) + ")";
  }
  return "uid " + std::to_string(uid);
}

// What to do about an SQLite error `code` on the store file `path`, in plain words.
std::string Remedy(int code, const std::string& path) {
  const std::string dir = fs::path(path).parent_path().string();
  switch (code & 0xff) {
    case SQLITE_CANTOPEN:
    case SQLITE_PERM:
    case SQLITE_READONLY:
    case SQLITE_AUTH:
      return "check the owner and mode of " + path + " (and of its -wal and -shm files) and of " +
             dir + ": atlasd runs as " + RunningAs() + " and must be able to read and write them";
    case SQLITE_BUSY:
    case SQLITE_LOCKED:
      return "another process holds the store locked (a second atlasd on the same "
             "state.directory, or a tool that has it open): stop that process, then try again";
    case SQLITE_IOERR:
      return "the operating system reported an I/O error: check the disk and the kernel log "
             "(dmesg), then try again";
    case SQLITE_FULL:
      return "the disk is full: free some space on it, then try again";
    case SQLITE_NOMEM:
      return "the process ran out of memory: free some, then try again";
    default:
      return "fix the cause, then try again";
  }
}

// The message of a state directory that cannot be searched or created.
std::string DirectoryProblem(const std::string& directory, const std::string& error) {
  return "cannot access state.directory " + directory + ": " + error +
         "; check the owner and mode of " + directory +
         " and of the directories above it: " + "atlasd runs as " + RunningAs() +
         " and must be able to search and write it";
}

// Finds the store file: *size is 0 when there is none. False with *error when that cannot be
// told, or when path is something else than a regular file.
bool FindStoreFile(const std::string& directory, const std::string& path, uintmax_t* size,
                   std::string* error) {
  *size = 0;
  std::error_code ec;
  const fs::file_status st = fs::status(path, ec);
  if (st.type() == fs::file_type::not_found) return true;
  if (ec) {
    *error = DirectoryProblem(directory, ec.message());
    return false;
  }
  if (st.type() != fs::file_type::regular) {
    *error = path + " is not a regular file (a directory or a special file stands in its place)" +
             "; it was left as it is: move it away, then try again";
    return false;
  }
  *size = fs::file_size(path, ec);
  if (ec) {
    *error = DirectoryProblem(directory, ec.message());
    return false;
  }
  return true;
}

// A file: URI for path (RFC 3986 escapes for the characters SQLite's URI parser gives meaning
// to).
std::string FileUri(const std::string& path) {
  std::string uri = path.starts_with('/') ? "file://" : "file:";
  for (const char c : path) {
    if (c == '%') {
      uri += "%25";
    } else if (c == '?') {
      uri += "%3f";
    } else if (c == '#') {
      uri += "%23";
    } else {
      uri += c;
    }
  }
  return uri;
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
  error_code_ = sqlite3_extended_errcode(db_);
  *error = msg != nullptr ? msg : ErrorText(db_);
  sqlite3_free(msg);
  return false;
}

// Checks on a read-only connection, so that checking never writes to the file. A WAL file left
// by a killed process may need recovery, which a read-only connection cannot do (SQLITE_READONLY
// and its extended codes): then the check runs on a read-write connection that recovers the WAL
// index, but does not checkpoint into the main file when it closes.
//
// Only what shows that the file itself is bad makes it kNotOurs: SQLite finding it corrupt or not
// a database, a failed integrity_check, a missing schema. Any other failure (the file cannot be
// opened, is locked, an I/O error, no memory, ...) says nothing about the file: kUnreadable, with
// the SQLite error in *why and its code in *code.
AtlasStore::Check AtlasStore::CheckExisting(std::string* why, int* found_version, int* code) {
  for (const bool read_only : {true, false}) {
    Check verdict = Check::kOurs;
    std::string error;
    sqlite3* db = nullptr;
    int rc = sqlite3_open_v2(path_.c_str(), &db,
                             read_only ? SQLITE_OPEN_READONLY : SQLITE_OPEN_READWRITE, nullptr);
    if (rc == SQLITE_OK) {
      sqlite3_busy_timeout(db, 2000);
      if (!read_only) sqlite3_db_config(db, SQLITE_DBCONFIG_NO_CKPT_ON_CLOSE, 1, nullptr);
      rc = CheckConnection(db, why, found_version, &verdict, &error);
    } else {
      error = ErrorText(db);
    }
    sqlite3_close(db);
    if (read_only && (rc & 0xff) == SQLITE_READONLY) continue;  // needs recovery: retry writable
    if (rc == SQLITE_OK) return verdict;
    *code = rc;
    if (IsCorruption(rc)) {
      *why = (rc & 0xff) == SQLITE_NOTADB ? "it is not an SQLite database"
                                          : "SQLite finds it corrupt (" + error + ")";
      return Check::kNotOurs;
    }
    *why = error;
    break;
  }
  return Check::kUnreadable;
}

// Runs integrity_check and reads schema_version; returns the SQLite code of a failure to read
// (with *error saying what it was), or SQLITE_OK with *verdict set.
int AtlasStore::CheckConnection(sqlite3* db, std::string* why, int* found_version, Check* verdict,
                                std::string* error) {
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
  if (rc != SQLITE_OK) *error = ErrorText(db);
  sqlite3_finalize(st);
  if (rc != SQLITE_OK || *verdict != Check::kOurs) return rc;

  // A database without any table is a store whose creation was interrupted (the schema is
  // created in one transaction, after the journal mode): it is simply created again.
  st = nullptr;
  rc = sqlite3_prepare_v2(db, "SELECT count(*) FROM sqlite_master", -1, &st, nullptr);
  if (rc == SQLITE_OK) rc = sqlite3_step(st) == SQLITE_ROW ? SQLITE_OK : sqlite3_errcode(db);
  const bool no_tables = rc == SQLITE_OK && sqlite3_column_int(st, 0) == 0;
  if (rc != SQLITE_OK) *error = ErrorText(db);
  sqlite3_finalize(st);
  if (rc != SQLITE_OK) return rc;
  if (no_tables) {
    *verdict = Check::kEmpty;
    return SQLITE_OK;
  }

  // No such table (SQLITE_ERROR) or no row: not our schema. Any other failure is a failure to
  // read, not a verdict on the file.
  st = nullptr;
  rc = sqlite3_prepare_v2(db, "SELECT version FROM schema_version", -1, &st, nullptr);
  if (rc == SQLITE_OK) rc = sqlite3_step(st);
  if (rc == SQLITE_ERROR || rc == SQLITE_DONE) {
    *why = "it has no schema_version: it is not an atlasd store";
    *verdict = Check::kNotOurs;
    rc = SQLITE_OK;
  } else if (rc == SQLITE_ROW) {
    *found_version = sqlite3_column_int(st, 0);
    if (*found_version > kSchemaVersion) {
      *why = "it was written by a newer atlasd (schema version " + std::to_string(*found_version) +
             "; this atlasd reads up to " + std::to_string(kSchemaVersion) + ")";
      *verdict = Check::kNewer;
    } else if (*found_version < 1) {
      *why = "its schema_version " + std::to_string(*found_version) + " is invalid";
      *verdict = Check::kNotOurs;
    }
    rc = SQLITE_OK;
  } else {
    *error = ErrorText(db);
  }
  sqlite3_finalize(st);
  return rc;
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
    const int code = error_code_;
    Exec("ROLLBACK", &ignored);
    error_code_ = code;
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
      error_code_ = sqlite3_extended_errcode(db_);
      *error = ErrorText(db_);
      return false;
    }
  }
  return true;
}

StoreOpenResult AtlasStore::Open(const std::string& directory) {
  Close();
  read_only_ = false;
  StoreOpenResult result;
  std::error_code ec;
  fs::create_directories(directory, ec);
  if (ec) {
    result.message = "cannot create the state directory " + directory + ": " + ec.message() +
                     "; check the owner and mode of the directories above it: atlasd runs as " +
                     RunningAs();
    return result;
  }
  path_ = (fs::path(directory) / kFileName).string();
  uintmax_t size = 0;
  if (!FindStoreFile(directory, path_, &size, &result.message)) return result;
  const bool existed = size > 0;
  // An empty main file beside a write-ahead log that holds data (a writer killed before the
  // first checkpoint wrote the header): SQLite would open it as a new database and delete the
  // log, so the pair is refused and kept like any corrupt store.
  const uintmax_t wal_size = existed ? 0 : fs::file_size(path_ + "-wal", ec);
  const bool orphan_wal = !existed && !ec && wal_size > 0;

  result.status = existed ? StoreOpenStatus::kOpened : StoreOpenStatus::kCreated;
  if (existed || orphan_wal) {
    std::string why;
    int version = 0;
    int code = SQLITE_OK;
    Check check = Check::kNotOurs;
    if (orphan_wal) {
      why = "its main file is empty beside a write-ahead log of " + std::to_string(wal_size) +
            " bytes (written by an atlasd stopped before its first checkpoint)";
    } else {
      check = CheckExisting(&why, &version, &code);
    }
    if (check == Check::kUnreadable) {
      result.status = StoreOpenStatus::kFailed;
      result.message = "cannot read the atlas store " + path_ + " (" + why +
                       "); it was left as it is (nothing moved or changed): " + Remedy(code, path_);
      return result;
    }
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
  error_code_ = SQLITE_OK;
  if (sqlite3_open_v2(path_.c_str(), &db_, SQLITE_OPEN_READWRITE | SQLITE_OPEN_CREATE, nullptr) !=
          SQLITE_OK ||
      !Configure(&error) || !CreateSchema(&error) || !Prepare(&error)) {
    if (error.empty()) error = ErrorText(db_);
    int code = error_code_;
    if (code == SQLITE_OK) code = db_ != nullptr ? sqlite3_extended_errcode(db_) : SQLITE_NOMEM;
    Close();
    result.status = StoreOpenStatus::kFailed;
    result.message =
        "cannot open the atlas store " + path_ + ": " + error + "; " + Remedy(code, path_) +
        (result.moved_to.empty() ? "" : " (the refused file is " + result.moved_to + ")");
    return result;
  }
  if (result.status == StoreOpenStatus::kOpened) {
    result.message = "opened the atlas store " + path_;
  } else if (result.status == StoreOpenStatus::kCreated) {
    result.message = "created a new atlas store " + path_;
  }
  return result;
}

StoreOpenResult AtlasStore::OpenReadOnly(const std::string& directory) {
  Close();
  read_only_ = true;
  StoreOpenResult result;
  path_ = (fs::path(directory) / kFileName).string();
  std::error_code ec;
  const fs::file_status dir = fs::status(directory, ec);
  if (dir.type() == fs::file_type::not_found) {
    result.message = "there is no saved atlas: the state directory " + directory +
                     " does not exist (check state.directory in the configuration)";
    return result;
  }
  if (ec) {
    result.message = DirectoryProblem(directory, ec.message());
    return result;
  }
  if (dir.type() != fs::file_type::directory) {
    result.message = "state.directory " + directory + " is not a directory";
    return result;
  }
  uintmax_t size = 0;
  if (!FindStoreFile(directory, path_, &size, &result.message)) return result;
  bool present = true;
  if (size == 0 && (!Exists(path_, &present, &result.message) || !present)) {
    if (!present) result.message = "there is no saved atlas: " + path_ + " does not exist";
    return result;
  }
  if (size == 0) {
    result.message = "there is no saved atlas: " + path_ + " is empty";
    return result;
  }
  // Without a -wal file the last connection checkpointed everything into the main file, which
  // is then read as an immutable file (a read-only connection would otherwise create -wal and
  // -shm files, owned by whoever runs the export). With one, the existing -wal and -shm are
  // read as they are (readonly_shm: the -shm is never created or written).
  bool wal = false;
  if (!Exists(path_ + "-wal", &wal, &result.message)) {
    result.message = DirectoryProblem(directory, result.message);
    return result;
  }
  const std::string uri = FileUri(path_) + (wal ? "?mode=ro&readonly_shm=1" : "?immutable=1");
  Check verdict = Check::kOurs;
  std::string why, error;
  int version = 0;
  int rc = sqlite3_open_v2(uri.c_str(), &db_, SQLITE_OPEN_READONLY | SQLITE_OPEN_URI, nullptr);
  if (rc == SQLITE_OK) {
    sqlite3_busy_timeout(db_, 2000);
    rc = CheckConnection(db_, &why, &version, &verdict, &error);
  } else {
    error = ErrorText(db_);
  }
  if (rc != SQLITE_OK) {
    Close();
    result.message = "cannot read the atlas store " + path_ + " (" + error + "); ";
    if (IsCorruption(rc)) {
      result.message += "SQLite finds it corrupt";
    } else {
      result.message += Remedy(rc, path_);
      const int primary = rc & 0xff;
      if (wal && (primary == SQLITE_CANTOPEN || primary == SQLITE_READONLY)) {
        result.message += "; if they are readable, its write-ahead log " + path_ +
                          "-wal needs a recovery that a read-only reader cannot do: start " +
                          "atlasd once (it recovers the log), stop it, and export again";
      }
    }
    result.message += " (nothing was changed)";
    return result;
  }
  if (verdict != Check::kOurs) {
    Close();
    result.message =
        verdict == Check::kEmpty
            ? "there is no saved atlas: " + path_ + " holds no table yet"
            : "refused the atlas store " + path_ + " because " + why +
                  " (it was left as it is; atlasd moves such a file aside when it starts)";
    return result;
  }
  result.status = StoreOpenStatus::kOpened;
  result.message = "opened the atlas store " + path_ + " read-only";
  return result;
}

StoreOpenResult AtlasStore::RefuseAndStartEmpty(bool newer, const std::string& why) {
  StoreOpenResult result;
  if (db_ == nullptr || read_only_) {
    result.message = db_ == nullptr ? "the atlas store is not open"
                                    : "the atlas store " + path_ + " is open read-only";
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
  if (db_ == nullptr || read_only_) {
    *error = db_ == nullptr ? "the atlas store is not open"
                            : "the atlas store " + path_ + " is open read-only";
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
