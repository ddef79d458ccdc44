#pragma once
// What a fake device sent, bounded: the fakes may play for hours (atlas-fakedev, the
// hardware-in-loop bench), so each keeps only the LAST `capacity` items it recorded, oldest
// first, and counts every item ever recorded. Items older than the last `capacity` are dropped
// (dropped() = total() - size). Capacity 0 keeps nothing and only counts. Memory is bounded by
// `capacity` items; the storage grows to it as items come and is reused after that.
//
// Thread-safe: one thread may Add() while others read.

#include <cstddef>
#include <cstdint>
#include <mutex>
#include <utility>
#include <vector>

namespace atlas::fake {

// The fakes' default: more than the whole of mit-csail sends (21,200 AgileX 0x311 frames, the
// most numerous record), so tests of a whole log still see everything.
inline constexpr size_t kDefaultSentRecordCapacity = 32768;

template <typename T>
class SentRecord {
 public:
  explicit SentRecord(size_t capacity) : capacity_(capacity) {}

  void Add(T item) {
    std::lock_guard<std::mutex> lock(mutex_);
    ++total_;
    if (capacity_ == 0) return;
    if (items_.size() < capacity_) {
      items_.push_back(std::move(item));
      return;
    }
    items_[oldest_] = std::move(item);
    oldest_ = (oldest_ + 1) % capacity_;
  }

  // The items kept, oldest first (the last min(total(), capacity()) recorded, in order).
  std::vector<T> Items() const {
    std::lock_guard<std::mutex> lock(mutex_);
    std::vector<T> out;
    out.reserve(items_.size());
    for (size_t i = 0; i < items_.size(); ++i) out.push_back(items_[(oldest_ + i) % items_.size()]);
    return out;
  }

  // Every item recorded, kept or dropped.
  uint64_t total() const {
    std::lock_guard<std::mutex> lock(mutex_);
    return total_;
  }
  uint64_t dropped() const {
    std::lock_guard<std::mutex> lock(mutex_);
    return total_ - items_.size();
  }
  size_t capacity() const { return capacity_; }

 private:
  const size_t capacity_;
  mutable std::mutex mutex_;
  std::vector<T> items_;  // a ring once full: items_[oldest_] is the oldest
  size_t oldest_ = 0;
  uint64_t total_ = 0;
};

}  // namespace atlas::fake
