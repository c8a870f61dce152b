#include "mocaplink/core/late_frames.hpp"

#include <gtest/gtest.h>

namespace mocaplink::core {
namespace {

using namespace std::chrono_literals;

const HostTime t0{std::chrono::seconds(1000)};

TEST(LateFrames, AFrameIsLateOnlyOnceItWaitedLongerThanTheLimit) {
  LateFrames late;
  EXPECT_FALSE(late.skip_if_late(t0, t0));
  EXPECT_FALSE(late.skip_if_late(t0, t0 + 249ms));
  EXPECT_FALSE(late.skip_if_late(t0, t0 + 250ms));  // exactly the limit: still in time
  EXPECT_EQ(late.skipped(), 0u);
  EXPECT_TRUE(late.skip_if_late(t0, t0 + 250ms + 1ns));
  EXPECT_TRUE(late.skip_if_late(t0, t0 + 2s));
  EXPECT_EQ(late.skipped(), 2u);
  // A frame stamped after the loop's clock read (another thread's clock read, later) is in time.
  EXPECT_FALSE(late.skip_if_late(t0 + 1ms, t0));
  EXPECT_EQ(late.skipped(), 2u);
}

TEST(LateFrames, TheLimitIsTheOneGiven) {
  LateFrames late(10ms);
  EXPECT_FALSE(late.skip_if_late(t0, t0 + 10ms));
  EXPECT_TRUE(late.skip_if_late(t0, t0 + 11ms));
  EXPECT_EQ(late.skipped(), 1u);
}

TEST(LateFrames, WarnsAtOnceThenAtMostEveryPeriodWithWhatWasSkippedSince) {
  LateFrames late;
  EXPECT_FALSE(late.warning(t0).has_value());  // nothing skipped: nothing to say
  ASSERT_TRUE(late.skip_if_late(t0, t0 + 300ms));
  const auto first = late.warning(t0 + 300ms);
  ASSERT_TRUE(first.has_value());
  EXPECT_EQ(first->skipped, 1u);
  EXPECT_EQ(first->oldest, 300ms);
  EXPECT_FALSE(late.warning(t0 + 301ms).has_value());  // said already

  // Three more within the period: held back until it has passed, then all of them at once.
  ASSERT_TRUE(late.skip_if_late(t0 + 1s, t0 + 1s + 400ms));
  ASSERT_TRUE(late.skip_if_late(t0 + 2s, t0 + 2s + 900ms));
  ASSERT_TRUE(late.skip_if_late(t0 + 3s, t0 + 3s + 500ms));
  EXPECT_FALSE(late.warning(t0 + 5s).has_value());
  EXPECT_FALSE(late.warning(t0 + 300ms + kLateWarningPeriod - 1ns).has_value());
  const auto second = late.warning(t0 + 300ms + kLateWarningPeriod);
  ASSERT_TRUE(second.has_value());
  EXPECT_EQ(second->skipped, 3u);
  EXPECT_EQ(second->oldest, 900ms);
  EXPECT_EQ(late.skipped(), 4u);

  // Quiet for longer than the period: the next skip is warned about at once, counted afresh.
  EXPECT_FALSE(late.warning(t0 + 60s).has_value());
  ASSERT_TRUE(late.skip_if_late(t0 + 61s, t0 + 61s + 260ms));
  const auto third = late.warning(t0 + 61s + 260ms);
  ASSERT_TRUE(third.has_value());
  EXPECT_EQ(third->skipped, 1u);
  EXPECT_EQ(third->oldest, 260ms);
}

}  // namespace
}  // namespace mocaplink::core
