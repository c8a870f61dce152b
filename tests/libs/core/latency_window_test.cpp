// LatencyWindow: last / p50 / p99 / max over the latest kLatencyWindowSize samples (nearest rank).
#include "mocaplink/core/latency_window.hpp"

#include <gtest/gtest.h>

namespace mocaplink::core {
namespace {

using std::chrono::microseconds;

TEST(LatencyWindow, NothingBeforeTheFirstSample) {
  const LatencyWindow window;
  EXPECT_FALSE(window.summary().has_value());
}

TEST(LatencyWindow, PercentilesByNearestRank) {
  LatencyWindow window;
  // 1..100 µs in a shuffled order, last one 37 µs.
  for (int i = 0; i < 100; ++i) window.add(microseconds((i * 37) % 100 + 1));
  const auto s = window.summary();
  ASSERT_TRUE(s);
  EXPECT_EQ(s->samples, 100U);
  EXPECT_EQ(s->last, microseconds((99 * 37) % 100 + 1));
  EXPECT_EQ(s->p50, microseconds(50));
  EXPECT_EQ(s->p99, microseconds(99));
  EXPECT_EQ(s->max, microseconds(100));
}

TEST(LatencyWindow, OnlyTheLatestSamplesCount) {
  LatencyWindow window;
  window.add(microseconds(1'000'000));  // one huge old sample
  for (std::size_t i = 0; i < kLatencyWindowSize; ++i) window.add(microseconds(10));
  const auto s = window.summary();
  ASSERT_TRUE(s);
  EXPECT_EQ(s->samples, kLatencyWindowSize);
  EXPECT_EQ(s->max, microseconds(10));
  EXPECT_EQ(s->p99, microseconds(10));
}

}  // namespace
}  // namespace mocaplink::core
