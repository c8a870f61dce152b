#include "mocaplink/core/ring.hpp"

#include <deque>
#include <random>

#include <gtest/gtest.h>

namespace mocaplink::core {
namespace {

// Against std::deque as the oracle: random pushes and pops, through several growths.
TEST(Ring, BehavesAsADequeQueue) {
  Ring<int> ring;
  std::deque<int> oracle;
  std::mt19937 random(7);
  int next = 0;
  for (int step = 0; step < 20000; ++step) {
    // More pushes than pops while the ring is small, then balanced: it grows, then wraps.
    const bool push = oracle.empty() || random() % 100 < (step < 5000 ? 70U : 50U);
    if (push) {
      ring.push_back(next);
      oracle.push_back(next);
      ++next;
    } else {
      ring.pop_front();
      oracle.pop_front();
    }
    ASSERT_EQ(ring.size(), oracle.size());
    if (!oracle.empty()) {
      ASSERT_EQ(ring.front(), oracle.front());
      ASSERT_EQ(ring.back(), oracle.back());
      const std::size_t i = random() % oracle.size();
      ASSERT_EQ(ring[i], oracle[i]);
    }
  }
}

TEST(Ring, StopsGrowingOnceItHasHeldItsMost) {
  Ring<int> ring;
  EXPECT_EQ(ring.capacity(), 0u);
  for (int i = 0; i < 100; ++i) ring.push_back(i);
  const std::size_t capacity = ring.capacity();
  EXPECT_GE(capacity, 100u);
  for (int i = 100; i < 100000; ++i) {  // a sliding window of 100
    ring.pop_front();
    ring.push_back(i);
  }
  EXPECT_EQ(ring.capacity(), capacity);
  EXPECT_EQ(ring.front(), 99900);
  ring.clear();
  EXPECT_TRUE(ring.empty());
  EXPECT_EQ(ring.capacity(), capacity);
}

}  // namespace
}  // namespace mocaplink::core
