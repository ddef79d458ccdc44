#pragma once
// A fixed-capacity, lock-free single-producer single-consumer queue that never blocks the
// consumer and, when full, drops the OLDEST element and counts it.
//
// Design: the bounded ring of D. Vyukov ("bounded MPMC queue"), one sequence number per slot.
// Slot i of position p is free for the producer when seq == p, holds data when seq == p + 1,
// and is released for the next lap with seq = p + capacity. The consumer claims the oldest
// position with a CAS on the read index, moves the element out, then releases the slot.
// When the queue is full the producer acts as a second consumer: it claims the oldest
// position with the same CAS and discards the element (counted in Dropped()). Ownership of a
// slot's value is always handed over by a release store of seq and an acquire load of it, so
// there is no data race on the values.
//
// Contract: exactly one thread calls Push, exactly one thread calls Pop. Push never waits for
// the consumer except in one case: the slot it must overwrite is being moved out by a Pop in
// progress at that very moment; it then spins for the duration of that move (one move of T).
// Pop never waits. Counters may be read from any thread.

#include <atomic>
#include <cstddef>
#include <cstdint>
#include <memory>
#include <new>
#include <thread>
#include <utility>

namespace atlas {

template <typename T>
class SpscQueue {
 public:
  // `capacity` is rounded up to a power of two, at least 2.
  explicit SpscQueue(size_t capacity) {
    size_t c = 2;
    while (c < capacity) c <<= 1;
    capacity_ = c;
    mask_ = c - 1;
    slots_ = std::make_unique<Slot[]>(c);
    for (size_t i = 0; i < c; ++i) slots_[i].seq.store(i, std::memory_order_relaxed);
  }
  SpscQueue(const SpscQueue&) = delete;
  SpscQueue& operator=(const SpscQueue&) = delete;

  size_t capacity() const { return capacity_; }

  // Producer only. Returns true if an older element had to be dropped to make room.
  bool Push(T value) {
    const uint64_t pos = write_.load(std::memory_order_relaxed);
    Slot& slot = slots_[pos & mask_];
    bool dropped = false;
    for (;;) {
      const uint64_t seq = slot.seq.load(std::memory_order_acquire);
      if (seq == pos) break;  // free
      // The slot still holds position pos - capacity (full), or a Pop is moving it out.
      const uint64_t oldest = pos - capacity_;
      if (read_.load(std::memory_order_relaxed) <= oldest) {
        T discard;
        if (TryClaim(&discard)) {
          dropped_.fetch_add(1, std::memory_order_relaxed);
          dropped = true;
        }
      } else {
        std::this_thread::yield();  // a Pop is moving the oldest out right now
      }
    }
    slot.value = std::move(value);
    slot.seq.store(pos + 1, std::memory_order_release);
    write_.store(pos + 1, std::memory_order_relaxed);
    pushed_.fetch_add(1, std::memory_order_relaxed);
    return dropped;
  }

  // Consumer only. Moves the oldest element into *out; false when empty. Never blocks.
  bool Pop(T* out) {
    if (!TryClaim(out)) return false;
    popped_.fetch_add(1, std::memory_order_relaxed);
    return true;
  }

  uint64_t Pushed() const { return pushed_.load(std::memory_order_relaxed); }
  uint64_t Popped() const { return popped_.load(std::memory_order_relaxed); }
  uint64_t Dropped() const { return dropped_.load(std::memory_order_relaxed); }
  // Approximate when called concurrently with Push or Pop.
  size_t SizeApprox() const {
    const uint64_t w = write_.load(std::memory_order_relaxed);
    const uint64_t r = read_.load(std::memory_order_relaxed);
    return w > r ? static_cast<size_t>(w - r) : 0;
  }

 private:
  struct Slot {
    std::atomic<uint64_t> seq{0};
    T value{};
  };

  // Claims the oldest filled position (consumer or dropping producer) and moves it out.
  bool TryClaim(T* out) {
    uint64_t pos = read_.load(std::memory_order_relaxed);
    for (;;) {
      Slot& slot = slots_[pos & mask_];
      const uint64_t seq = slot.seq.load(std::memory_order_acquire);
      const int64_t diff = static_cast<int64_t>(seq) - static_cast<int64_t>(pos + 1);
      if (diff == 0) {
        if (read_.compare_exchange_weak(pos, pos + 1, std::memory_order_relaxed)) {
          *out = std::move(slot.value);
          slot.seq.store(pos + capacity_, std::memory_order_release);
          return true;
        }
      } else if (diff < 0) {
        return false;  // empty
      } else {
        pos = read_.load(std::memory_order_relaxed);
      }
    }
  }

  size_t capacity_ = 0;
  size_t mask_ = 0;
  std::unique_ptr<Slot[]> slots_;
  alignas(64) std::atomic<uint64_t> write_{0};
  alignas(64) std::atomic<uint64_t> read_{0};
  alignas(64) std::atomic<uint64_t> pushed_{0};
  std::atomic<uint64_t> popped_{0};
  std::atomic<uint64_t> dropped_{0};
};

}  // namespace atlas
