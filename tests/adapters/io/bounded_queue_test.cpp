#include "mocaplink/io/bounded_queue.hpp"

#include <thread>
#include <vector>

#include <gtest/gtest.h>

namespace mocaplink::io {
namespace {

TEST(BoundedQueue, WakesOnlyOnEmptyToNonEmpty) {
  BoundedQueue<int> q(4);
  EXPECT_TRUE(q.push(1));
  EXPECT_FALSE(q.push(2));
  std::vector<int> out;
  EXPECT_EQ(q.drain(out), 2u);
  EXPECT_EQ(out, (std::vector<int>{1, 2}));
  EXPECT_TRUE(q.push(3));
}

TEST(BoundedQueue, OverflowDropsOldestAndCounts) {
  BoundedQueue<int> q(3);
  for (int i = 1; i <= 5; ++i) (void)q.push(i);
  EXPECT_EQ(q.overflows(), 2u);
  EXPECT_EQ(q.size(), 3u);
  std::vector<int> out;
  (void)q.drain(out);
  EXPECT_EQ(out, (std::vector<int>{3, 4, 5}));
}

TEST(BoundedQueue, ZeroCapacityHoldsOne) {
  BoundedQueue<int> q(0);
  EXPECT_EQ(q.capacity(), 1u);
  (void)q.push(1);
  (void)q.push(2);
  std::vector<int> out;
  (void)q.drain(out);
  EXPECT_EQ(out, (std::vector<int>{2}));
  EXPECT_EQ(q.overflows(), 1u);
}

TEST(BoundedQueue, ConcurrentProducersLoseNothingBelowCapacity) {
  constexpr int kPerThread = 5000;
  BoundedQueue<int> q(4 * kPerThread);
  std::vector<std::thread> producers;
  for (int t = 0; t < 4; ++t) {
    producers.emplace_back([&q, t] {
      for (int i = 0; i < kPerThread; ++i) (void)q.push(t * kPerThread + i);
    });
  }
  std::vector<int> out;
  for (auto& p : producers) p.join();
  (void)q.drain(out);
  EXPECT_EQ(out.size(), 4u * kPerThread);
  EXPECT_EQ(q.overflows(), 0u);
  // Each producer's items keep their order.
  std::vector<int> last(4, -1);
  for (const int v : out) {
    const int t = v / kPerThread;
    EXPECT_GT(v, last[static_cast<std::size_t>(t)]);
    last[static_cast<std::size_t>(t)] = v;
  }
}

}  // namespace
}  // namespace mocaplink::io
