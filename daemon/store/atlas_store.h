#pragma once
// The saved atlas: an SQLite database <state directory>/atlas.sqlite holding the map-frames (each
// local map as its LocalMap::Serialize() byte image), the edges of the atlas graph, and
// metadata. A restart loads it; the robot then starts in a new frame and map-matching
// reconnects it to the saved ones (docs/atlasd.md, "Persistence").
//
// Contract:
// - Open() creates the file and schema when absent (or when the file holds no table at all: a
//   creation interrupted by a crash). An empty file beside a non-empty -wal (a writer killed
//   before its first checkpoint), a file that is not an SQLite database,
//   fails `PRAGMA integrity_check`, or lacks our schema is refused as corrupt; a file whose
//   schema_version is newer than kSchemaVersion is refused as newer. A refused file is never
//   overwritten: it is renamed (with its -wal and -shm companions) to
//   atlas.sqlite.<corrupt|newer>-YYYYMMDDTHHMMSSZ, the result says so in plain words, and the
//   store starts empty in a fresh file. Only those verdicts on the file move it: any other
//   failure to open or read it (permissions, a lock held by another process, an I/O error, no
//   memory, a directory in its place, a state directory that cannot be searched) leaves
//   everything as it is and fails (kFailed) with a message naming the file, the error and what
//   to do.
// - OpenReadOnly() (atlasd --export-atlas) reads an existing store and never creates, changes
//   or moves a file: a missing, unreadable, corrupt or newer store is only reported.
// - WAL journal, synchronous=NORMAL: a committed Save() survives kill -9 of the process
//   (not necessarily a power cut, which may lose the last transactions but never corrupts).
// - Save() writes one batch in one transaction: after a crash the store holds a prefix of the
//   batches, never part of one. Rows are upserted by key (frame id; edge (from, to); metadata
//   key), so a batch carries only what changed. Each Save() increments the metadata value
//   "batch_sequence".
// - Metadata values are byte strings (stored as BLOBs; binary values such as the atlas image
//   round-trip exactly, embedded NULs included).
// - SQLite is touched only by the thread that owns the store (the writer thread,
//   AtlasStoreWriter); never by the step loop. Not thread-safe.

#include <array>
#include <cstdint>
#include <map>
#include <string>
#include <vector>

struct sqlite3;
struct sqlite3_stmt;

namespace atlas {

struct StoredFrame {
  int32_t id = -1;
  std::string blob;        // LocalMap::Serialize() image
  int64_t updated_at = 0;  // set by Save(): Unix time, microseconds (for people, not the atlas)
};

struct StoredEdge {
  int32_t frame_from = -1;
  int32_t frame_to = -1;
  double x = 0.0;  // pose of frame_to in frame_from: metres, metres, radians
  double y = 0.0;
  double theta = 0.0;
  std::array<double, 9> covariance{};  // row-major 3x3 over (x, y, theta)
  int kind = 0;                        // EdgeKind as an integer (atlas_graph.h)
};

// One save batch: the frames and edges that changed, and metadata to set.
struct AtlasSnapshot {
  std::vector<StoredFrame> frames;
  std::vector<StoredEdge> edges;
  std::map<std::string, std::string> metadata;

  bool empty() const { return frames.empty() && edges.empty() && metadata.empty(); }
  // Folds a later batch into this one: rows of `later` replace rows with the same key.
  void MergeLater(AtlasSnapshot&& later);
};

// Everything the store holds, ordered by frame id and by (from, to).
struct StoredAtlas {
  std::vector<StoredFrame> frames;
  std::vector<StoredEdge> edges;
  std::map<std::string, std::string> metadata;
};

enum class StoreOpenStatus {
  kOpened,             // an existing store, checked
  kCreated,            // no store yet: a new empty one
  kMovedAsideCorrupt,  // refused as corrupt, renamed; a new empty store is open
  kMovedAsideNewer,    // refused as written by a newer atlasd, renamed; a new empty store is open
  kFailed,  // nothing is open (directory unusable, file unreadable or locked, rename failed, ...);
            // nothing was moved unless moved_to says so
};

struct StoreOpenResult {
  StoreOpenStatus status = StoreOpenStatus::kFailed;
  std::string message;   // plain words, for the log; always set
  std::string moved_to;  // the refused file's new path, when moved aside
  bool ok() const { return status != StoreOpenStatus::kFailed; }
};

class AtlasStore {
 public:
  static constexpr int kSchemaVersion = 1;
  static constexpr const char* kFileName = "atlas.sqlite";

  AtlasStore() = default;
  ~AtlasStore();
  AtlasStore(const AtlasStore&) = delete;
  AtlasStore& operator=(const AtlasStore&) = delete;

  // Opens <directory>/atlas.sqlite, creating the directory when needed.
  StoreOpenResult Open(const std::string& directory);
  // Opens an existing <directory>/atlas.sqlite for Load() only: kOpened, or kFailed with the
  // reason (no directory or file, unreadable, corrupt, newer, empty). Creates, changes and moves
  // nothing (not even -wal or -shm files: without a -wal file the main file is read as it is,
  // with one the existing -wal and -shm are read, not created). Save() then fails.
  StoreOpenResult OpenReadOnly(const std::string& directory);
  void Close();
  bool is_open() const { return db_ != nullptr; }
  const std::string& path() const { return path_; }

  // For a store whose file is sound but whose content its user cannot take (e.g. an atlas image
  // that does not decode, or one written by a newer atlasd): closes it, moves the file aside
  // like Open() does with a corrupt or newer file (never overwritten), and opens a new empty
  // store in its place. `why` completes "refused the atlas store PATH because ...".
  StoreOpenResult RefuseAndStartEmpty(bool newer, const std::string& why);

  // Writes the batch in one transaction. On failure nothing of the batch is kept and *error
  // says why.
  bool Save(const AtlasSnapshot& batch, std::string* error);
  bool Load(StoredAtlas* out, std::string* error);

 private:
  enum class Check { kOurs, kEmpty, kNotOurs, kNewer, kUnreadable };
  Check CheckExisting(std::string* why, int* found_version, int* code);
  static int CheckConnection(sqlite3* db, std::string* why, int* found_version, Check* verdict,
                             std::string* error);
  bool CreateSchema(std::string* error);
  bool Configure(std::string* error);
  bool Prepare(std::string* error);
  bool Exec(const char* sql, std::string* error);
  void FinalizeStatements();

  sqlite3* db_ = nullptr;
  bool read_only_ = false;
  int error_code_ = 0;  // extended SQLite code of the last failed Exec() or Prepare()
  std::string path_;
  sqlite3_stmt* upsert_frame_ = nullptr;
  sqlite3_stmt* upsert_edge_ = nullptr;
  sqlite3_stmt* upsert_metadata_ = nullptr;
  sqlite3_stmt* bump_sequence_ = nullptr;
};

const char* ToString(StoreOpenStatus s);

}  // namespace atlas
