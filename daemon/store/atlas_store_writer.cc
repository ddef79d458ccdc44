#include "daemon/store/atlas_store_writer.h"

#include <cassert>
#include <exception>
#include <string>

namespace atlas {

AtlasStoreWriter::AtlasStoreWriter(AtlasStore* store, int capacity,
                                   std::chrono::milliseconds retry_interval)
    : store_(store),
      capacity_(static_cast<size_t>(capacity < 1 ? 1 : capacity)),
      retry_interval_(retry_interval) {
  assert(store_ != nullptr);
}

AtlasStoreWriter::~AtlasStoreWriter() { Stop(); }

void AtlasStoreWriter::Start() {
  std::lock_guard<std::mutex> lock(mutex_);
  if (thread_.joinable()) return;
  stopping_ = false;
  thread_ = std::thread([this] {
    // Out of memory while merging or saving: the writer stops and says so in its stats (what
    // the store already holds stays), instead of terminating atlasd.
    try {
      Run();
    } catch (const std::exception& e) {
      std::lock_guard<std::mutex> lock(mutex_);
      ++stats_.errors;
      stats_.last_error = std::string("the writer stopped: ") + e.what();
      stopping_ = true;
      busy_ = false;
      idle_.notify_all();
    }
  });
}

SubmitResult AtlasStoreWriter::Submit(AtlasSnapshot batch) {
  std::lock_guard<std::mutex> lock(mutex_);
  if (stopping_) return SubmitResult::kStopped;
  SubmitResult result = SubmitResult::kQueued;
  if (queue_.size() >= capacity_) {
    if (queue_.size() >= 2) {
      queue_[0].MergeLater(std::move(queue_[1]));
      queue_.erase(queue_.begin() + 1);
      queue_.push_back(std::move(batch));
    } else {
      queue_.back().MergeLater(std::move(batch));
    }
    ++stats_.coalesced;
    result = SubmitResult::kCoalesced;
  } else {
    queue_.push_back(std::move(batch));
  }
  wake_.notify_one();
  return result;
}

void AtlasStoreWriter::Run() {
  std::unique_lock<std::mutex> lock(mutex_);
  while (true) {
    wake_.wait(lock, [&] { return stopping_ || !queue_.empty(); });
    if (queue_.empty()) break;  // stopping, and nothing left
    AtlasSnapshot batch = std::move(queue_.front());
    queue_.pop_front();
    busy_ = true;
    lock.unlock();
    std::string error;
    const bool saved = store_->Save(batch, &error);
    lock.lock();
    busy_ = false;
    if (saved) {
      ++stats_.saved;
    } else {
      ++stats_.errors;
      stats_.last_error = error;
      // Keep the changes: they go ahead of whatever came since (a later batch saved without
      // them could leave a row behind the image it goes with), and are retried; when stopping,
      // once more merged with the next batch, or dropped when none is left (the store keeps
      // the last batch it saved).
      if (!stopping_ || !queue_.empty()) {
        if (!queue_.empty()) {
          batch.MergeLater(std::move(queue_.front()));
          queue_.pop_front();
        }
        queue_.push_front(std::move(batch));
        if (stopping_) continue;
        idle_.notify_all();
        wake_.wait_for(lock, retry_interval_, [&] { return stopping_; });
        continue;
      }
    }
    if (queue_.empty()) idle_.notify_all();
  }
  idle_.notify_all();
}

bool AtlasStoreWriter::Flush(std::chrono::milliseconds timeout) {
  std::unique_lock<std::mutex> lock(mutex_);
  const uint64_t errors_before = stats_.errors;
  return idle_.wait_for(lock, timeout, [&] {
    return (queue_.empty() && !busy_) || stats_.errors != errors_before || !thread_.joinable();
  });
}

void AtlasStoreWriter::Stop() {
  {
    std::lock_guard<std::mutex> lock(mutex_);
    stopping_ = true;
  }
  wake_.notify_all();
  if (thread_.joinable()) thread_.join();
}

StoreWriterStats AtlasStoreWriter::Stats() const {
  std::lock_guard<std::mutex> lock(mutex_);
  StoreWriterStats s = stats_;
  s.queued = queue_.size();
  return s;
}

}  // namespace atlas
