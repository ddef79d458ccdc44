#include "drivers/queue/spsc_queue.h"

#include <gtest/gtest.h>

#include <atomic>
#include <thread>
#include <vector>

namespace atlas {
namespace {

TEST(SpscQueueTest, RoundsCapacityUpToPowerOfTwo) {
  SpscQueue<int> q(5);
  EXPECT_EQ(q.capacity(), 8u);
}

TEST(SpscQueueTest, FifoAndEmpty) {
  SpscQueue<int> q(4);
  int v = -1;
  EXPECT_FALSE(q.Pop(&v));
  for (int i = 0; i < 3; ++i) EXPECT_FALSE(q.Push(i));
  for (int i = 0; i < 3; ++i) {
    ASSERT_TRUE(q.Pop(&v));
    EXPECT_EQ(v, i);
  }
  EXPECT_FALSE(q.Pop(&v));
}

TEST(SpscQueueTest, FullDropsTheOldestAndCountsIt) {
  SpscQueue<int> q(4);
  for (int i = 0; i < 4; ++i) EXPECT_FALSE(q.Push(i));
  EXPECT_TRUE(q.Push(4));
  EXPECT_TRUE(q.Push(5));
  EXPECT_EQ(q.Dropped(), 2u);
  std::vector<int> got;
  int v;
  while (q.Pop(&v)) got.push_back(v);
  EXPECT_EQ(got, (std::vector<int>{2, 3, 4, 5}));
  EXPECT_EQ(q.Pushed(), 6u);
  EXPECT_EQ(q.Popped(), 4u);
}

TEST(SpscQueueTest, MovesNonTrivialValues) {
  SpscQueue<std::vector<float>> q(2);
  q.Push(std::vector<float>(361, 1.5f));
  q.Push(std::vector<float>(3, 2.0f));
  q.Push(std::vector<float>(7, 3.0f));  // drops the 361
  std::vector<float> v;
  ASSERT_TRUE(q.Pop(&v));
  EXPECT_EQ(v.size(), 3u);
  ASSERT_TRUE(q.Pop(&v));
  EXPECT_EQ(v.size(), 7u);
}

// Two threads: the producer pushes 0..N-1 as fast as it can into a small queue while the
// consumer pops at its own pace. Everything that comes out is strictly increasing, and
// popped + dropped + left over == pushed.
TEST(SpscQueueTest, StressOrderAndCountsAddUp) {
  constexpr uint64_t kN = 400000;
  SpscQueue<std::vector<uint64_t>> q(8);  // non-trivial values to catch torn moves
  std::atomic<bool> done{false};
  uint64_t popped = 0;
  uint64_t last = 0;
  bool first = true;
  bool order_ok = true;
  bool payload_ok = true;
  std::thread consumer([&] {
    std::vector<uint64_t> v;
    auto drain = [&] {
      while (q.Pop(&v)) {
        if (v.size() != 2 || v[1] != v[0] * 3 + 1) payload_ok = false;
        if (!first && v[0] <= last) order_ok = false;
        first = false;
        last = v[0];
        ++popped;
      }
    };
    uint64_t spins = 0;
    while (!done.load(std::memory_order_acquire)) {
      drain();
      if (++spins % 64 == 0) std::this_thread::yield();
    }
    drain();
  });
  uint64_t producer_drops = 0;
  for (uint64_t i = 0; i < kN; ++i) {
    if (q.Push(std::vector<uint64_t>{i, i * 3 + 1})) ++producer_drops;
  }
  done.store(true, std::memory_order_release);
  consumer.join();
  EXPECT_TRUE(order_ok);
  EXPECT_TRUE(payload_ok);
  EXPECT_EQ(q.Pushed(), kN);
  EXPECT_EQ(q.Popped(), popped);
  EXPECT_EQ(q.Dropped(), producer_drops);
  EXPECT_EQ(popped + q.Dropped(), kN);
  EXPECT_EQ(last, kN - 1);  // the newest element is never dropped
  EXPECT_GT(popped, 0u);
}

}  // namespace
}  // namespace atlas
