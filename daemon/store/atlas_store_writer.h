#pragma once
// The thread that saves the atlas: the step loop hands it snapshot batches and never waits for
// SQLite (docs/atlasd.md, "Persistence").
//
// Contract:
// - Submit() is O(1) apart from a merge when the queue is full; it never touches SQLite and
//   never blocks on I/O. The queue holds at most `capacity` batches; when it is full the two
//   oldest batches are merged into one (rows of the later replace rows with the same key), so
//   that no change is lost and memory stays bounded by the atlas itself; each merge is counted.
// - Batches are written in submission order, one transaction each (AtlasStore::Save).
// - A batch that fails to save is kept (merged ahead of the next) and retried after
//   retry_interval; failures are counted with the last error text. No batch is saved without
//   the ones submitted before it: the store holds a prefix of the batches.
// - Stop() writes what is queued and joins; the destructor calls it. A batch that fails then is
//   merged into the next and tried once more with it; the last one to fail is dropped.
// - The writer owns the store between Start() and Stop(): nobody else may use it meanwhile.

#include <chrono>
#include <condition_variable>
#include <cstdint>
#include <deque>
#include <mutex>
#include <string>
#include <thread>

#include "daemon/store/atlas_store.h"

namespace atlas {

struct StoreWriterStats {
  uint64_t saved = 0;      // batches committed
  uint64_t coalesced = 0;  // batches merged into another because the queue was full
  uint64_t errors = 0;     // failed save attempts
  size_t queued = 0;       // batches waiting now
  std::string last_error;  // empty if none yet
};

enum class SubmitResult { kQueued, kCoalesced, kStopped };

class AtlasStoreWriter {
 public:
  AtlasStoreWriter(AtlasStore* store, int capacity,
                   std::chrono::milliseconds retry_interval = std::chrono::seconds(1));
  ~AtlasStoreWriter();
  AtlasStoreWriter(const AtlasStoreWriter&) = delete;
  AtlasStoreWriter& operator=(const AtlasStoreWriter&) = delete;

  void Start();
  SubmitResult Submit(AtlasSnapshot batch);
  // Waits until everything submitted so far is saved (or has failed); false on timeout.
  bool Flush(std::chrono::milliseconds timeout);
  void Stop();
  StoreWriterStats Stats() const;

 private:
  void Run();

  AtlasStore* store_;
  const size_t capacity_;
  const std::chrono::milliseconds retry_interval_;
  mutable std::mutex mutex_;
  std::condition_variable wake_;
  std::condition_variable idle_;
  std::deque<AtlasSnapshot> queue_;
  bool stopping_ = false;
  bool busy_ = false;
  StoreWriterStats stats_;
  std::thread thread_;
};

}  // namespace atlas
