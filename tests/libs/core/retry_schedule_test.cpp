// RetrySchedule: the reconnect schedule of every source and link (issue 41), on its own numbers.
#include "mocaplink/core/retry_schedule.hpp"

#include <vector>

#include <gtest/gtest.h>

namespace mocaplink::core {
namespace {

using std::chrono::milliseconds;

std::vector<long> delays(RetrySchedule& s, int n) {
  std::vector<long> out;
  for (int i = 0; i < n; ++i) out.push_back(static_cast<long>(s.next().count()));
  return out;
}

TEST(RetrySchedule, AtOnceThenShortIntervalsThenDoublingToTheCap) {
  RetrySchedule s;  // 50 ms, then 200 ms until 5 s have been waited, then 400 ... 5000
  EXPECT_EQ(s.next(), milliseconds(50));
  for (int i = 0; i < 25; ++i) ASSERT_EQ(s.next(), milliseconds(200)) << i;
  EXPECT_EQ(s.waited(), milliseconds(5050));
  EXPECT_EQ(delays(s, 7), (std::vector<long>{400, 800, 1600, 3200, 5000, 5000, 5000}));
  EXPECT_EQ(s.attempts(), 33u);
}

TEST(RetrySchedule, ResetStartsAgainAtOnce) {
  RetrySchedule s;
  (void)delays(s, 40);
  s.reset();
  EXPECT_EQ(s.attempts(), 0u);
  EXPECT_EQ(s.waited(), milliseconds(0));
  EXPECT_EQ(delays(s, 3), (std::vector<long>{50, 200, 200}));
}

TEST(RetrySchedule, PolicyIsClamped) {
  RetrySchedule s(
      RetryPolicy{milliseconds(-5), milliseconds(0), milliseconds(-1), milliseconds(0)});
  EXPECT_EQ(s.policy().first, milliseconds(0));
  EXPECT_EQ(s.policy().fast, milliseconds(1));
  EXPECT_EQ(s.policy().fast_for, milliseconds(0));
  EXPECT_EQ(s.policy().max, milliseconds(1));
  EXPECT_EQ(delays(s, 3), (std::vector<long>{0, 1, 1}));
}

TEST(RetrySchedule, OldExponentialBackOffIsAPolicyToo) {
  // fast_for 0: straight to doubling (from 2 x fast), as the sources did before issue 41.
  RetrySchedule s(
      RetryPolicy{milliseconds(500), milliseconds(250), milliseconds(0), milliseconds(5000)});
  EXPECT_EQ(delays(s, 6), (std::vector<long>{500, 500, 1000, 2000, 4000, 5000}));
}

// The bound the issue asks for: an outage of T costs at most T + 0.2 s for the first seconds
// (and one cap's worth later). Outages of 0.3 s, 1 s and 6 s as in the loopback tests.
TEST(RetrySchedule, AnOutageCostsAtMostTheShortIntervalForTheFirstSeconds) {
  const RetryPolicy policy;
  for (long t_ms = 0; t_ms <= 5000; t_ms += 10) {
    const auto at = first_attempt_after(policy, milliseconds(t_ms));
    ASSERT_GE(at, milliseconds(t_ms));
    ASSERT_LE(at - milliseconds(t_ms), milliseconds(200)) << t_ms;
  }
  EXPECT_EQ(first_attempt_after(policy, milliseconds(300)), milliseconds(450));
  EXPECT_EQ(first_attempt_after(policy, milliseconds(1000)), milliseconds(1050));
  EXPECT_EQ(first_attempt_after(policy, milliseconds(6000)), milliseconds(6250));
  for (long t_ms = 5000; t_ms <= 60000; t_ms += 100) {
    ASSERT_LE(first_attempt_after(policy, milliseconds(t_ms)) - milliseconds(t_ms), policy.max)
        << t_ms;
  }
}

}  // namespace
}  // namespace mocaplink::core
