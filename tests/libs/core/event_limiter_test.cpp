// EventLimiter (event_limiter.hpp): one log line per kind and subject per second, and the last
// word of a burst kept. Injected time.
#include "mocaplink/core/event_limiter.hpp"

#include <gtest/gtest.h>

namespace mocaplink::core {
namespace {

using std::chrono::milliseconds;

HostTime at_ms(std::int64_t ms) {
  return HostTime{std::chrono::seconds(100) + milliseconds(ms)};
}

BridgeEvent agreement(std::string subject, std::string text) {
  return {BridgeEventKind::agreement, HostTime{}, 0, std::move(subject), std::move(text)};
}

TEST(EventLimiter, ABurstLogsItsFirstAndItsLastLine) {
  // A verdict named as each of the vehicle's parameters arrives, 100 ms apart: the first line at
  // once, the last once the second has passed, the two between counted.
  EventLimiter limiter;
  const auto first = limiter.offer(agreement("quad", "disagrees; no axis change needed"), at_ms(0));
  ASSERT_TRUE(first);
  EXPECT_EQ(first->suppressed, 0U);
  EXPECT_FALSE(limiter.offer(agreement("quad", "disagrees; heading unknown"), at_ms(100)));
  EXPECT_FALSE(limiter.offer(agreement("quad", "disagrees; heading not arrived"), at_ms(200)));
  EXPECT_FALSE(limiter.offer(agreement("quad", "named again: body_forward = +x"), at_ms(300)));
  EXPECT_TRUE(limiter.flush(at_ms(900)).empty());  // within the second
  const auto last = limiter.flush(at_ms(1000));
  ASSERT_EQ(last.size(), 1U);
  EXPECT_EQ(last[0].event.text, "named again: body_forward = +x");
  EXPECT_EQ(last[0].suppressed, 2U);
  EXPECT_TRUE(limiter.flush(at_ms(5000)).empty());  // given out once
  // The held one counts as logged at the flush: the next within a second of it is held again.
  EXPECT_FALSE(limiter.offer(agreement("quad", "agrees"), at_ms(1500)));
  EXPECT_EQ(limiter.flush(at_ms(2000)).at(0).event.text, "agrees");
}

TEST(EventLimiter, KindsAndSubjectsAreLimitedApart) {
  EventLimiter limiter;
  EXPECT_TRUE(limiter.offer(agreement("quad", "a"), at_ms(0)));
  EXPECT_TRUE(limiter.offer(agreement("rover", "a"), at_ms(10)));
  BridgeEvent lost{BridgeEventKind::body_lost, HostTime{}, std::nullopt, "quad", "lost"};
  EXPECT_TRUE(limiter.offer(lost, at_ms(20)));
  EXPECT_FALSE(limiter.offer(lost, at_ms(30)));
}

TEST(EventLimiter, ANewLineAfterTheSecondReplacesAHeldOne) {
  // Without a flush in between (a daemon whose tick was late), the newer line wins and the held
  // one is counted.
  EventLimiter limiter;
  (void)limiter.offer(agreement("quad", "1"), at_ms(0));
  EXPECT_FALSE(limiter.offer(agreement("quad", "2"), at_ms(500)));
  const auto third = limiter.offer(agreement("quad", "3"), at_ms(1200));
  ASSERT_TRUE(third);
  EXPECT_EQ(third->event.text, "3");
  EXPECT_EQ(third->suppressed, 1U);
  EXPECT_TRUE(limiter.flush(at_ms(9000)).empty());
}

TEST(EventLimiter, AtExitEveryHeldLineIsGivenOut) {
  EventLimiter limiter;
  (void)limiter.offer(agreement("quad", "1"), at_ms(0));
  (void)limiter.offer(agreement("quad", "2"), at_ms(100));
  EXPECT_TRUE(limiter.flush(at_ms(200)).empty());
  const auto out = limiter.flush(at_ms(200), true);
  ASSERT_EQ(out.size(), 1U);
  EXPECT_EQ(out[0].event.text, "2");
}

TEST(EventLimiter, QuietSubjectsAreForgottenButNotAHeldLine) {
  EventLimiter limiter;
  (void)limiter.offer(agreement("gone", "1"), at_ms(0));
  (void)limiter.offer(agreement("held", "1"), at_ms(0));
  (void)limiter.offer(agreement("held", "2"), at_ms(10));
  EXPECT_EQ(limiter.size(), 2U);
  limiter.forget_quiet(at_ms(120'000), std::chrono::minutes(1));
  EXPECT_EQ(limiter.size(), 1U);  // "held" still has its line to give
  EXPECT_EQ(limiter.flush(at_ms(120'000)).at(0).event.text, "2");
  limiter.forget_quiet(at_ms(240'000), std::chrono::minutes(1));
  EXPECT_EQ(limiter.size(), 0U);
}

}  // namespace
}  // namespace mocaplink::core
