// RateWindow: events per second over a fixed recent window, whenever it is asked (issue 29).
#include "mocaplink/core/rate_window.hpp"

#include <gtest/gtest.h>

namespace mocaplink::core {
namespace {

using std::chrono::milliseconds;

HostTime at_ms(std::int64_t ms) {
  return HostTime{milliseconds(ms)};
}

TEST(RateWindow, NothingOrOneEventIsZero) {
  RateWindow rate;
  EXPECT_EQ(rate.rate_hz(at_ms(0)), 0.0);
  rate.add(at_ms(0));
  EXPECT_EQ(rate.rate_hz(at_ms(500)), 0.0);
}

TEST(RateWindow, TheFirstQuestionAfterAStartReadsTheRateSoFar) {
  // 26 events 20 ms apart, asked once, right after the last: 50 Hz, not 0.
  RateWindow rate;
  for (int k = 0; k <= 25; ++k) rate.add(at_ms(20 * k));
  EXPECT_DOUBLE_EQ(rate.rate_hz(at_ms(500)), 50.0);
}

TEST(RateWindow, SteadyRateWhoeverAsksWhenever) {
  RateWindow rate;
  for (int k = 0; k <= 500; ++k) rate.add(at_ms(20 * k));  // 10 s at 50 Hz
  // Asked right after an event: exactly 50; between two: at most one event low, never high.
  EXPECT_DOUBLE_EQ(rate.rate_hz(at_ms(10'000)), 50.0);
  for (int ms = 9'981; ms < 10'000; ms += 3) {
    // Asking does not change the figure (const): the same moment reads the same twice.
    EXPECT_EQ(rate.rate_hz(at_ms(ms)), rate.rate_hz(at_ms(ms)));
    EXPECT_LE(rate.rate_hz(at_ms(ms)), 50.0) << ms;
    EXPECT_GE(rate.rate_hz(at_ms(ms)), 49.0) << ms;
  }
}

TEST(RateWindow, OnlyTheLastWindowCounts) {
  RateWindow rate;
  for (int k = 0; k < 100; ++k) rate.add(at_ms(10 * k));          // 1 s at 100 Hz
  for (int k = 0; k <= 50; ++k) rate.add(at_ms(1'000 + 20 * k));  // then 1 s at 50 Hz
  EXPECT_DOUBLE_EQ(rate.rate_hz(at_ms(2'000)), 50.0);
}

TEST(RateWindow, FallsToZeroWithinAWindowWhenEventsStop) {
  RateWindow rate;
  for (int k = 0; k <= 50; ++k) rate.add(at_ms(20 * k));  // until t = 1 s
  EXPECT_DOUBLE_EQ(rate.rate_hz(at_ms(1'000)), 50.0);
  // The 25 events in (0.5 s, 1.5 s], from 0.52 s: 24 / 0.98 s.
  EXPECT_NEAR(rate.rate_hz(at_ms(1'500)), 24.0 / 0.98, 1e-9);
  EXPECT_EQ(rate.rate_hz(at_ms(2'001)), 0.0);
}

TEST(RateWindow, KeepsAtMostMaxEvents) {
  RateWindow rate(std::chrono::seconds(1), 11);
  for (int k = 0; k <= 100; ++k) rate.add(at_ms(10 * k));
  // Only the last 11 events (100 ms) are kept: they still read their own rate.
  EXPECT_DOUBLE_EQ(rate.rate_hz(at_ms(1'000)), 100.0);
}

TEST(AverageRate, AWholeRunsAverageIsNotItsLastSecond) {
  // 559 poses in a 12 s run that sent 50 Hz for 11.18 s: 46.6 Hz over the run, whatever the
  // last second's rate was (issue 29: the final line gave 50.6 Hz, the last second's).
  EXPECT_NEAR(average_rate_hz(559, std::chrono::seconds(12)), 46.58, 0.01);
  EXPECT_EQ(average_rate_hz(0, std::chrono::seconds(12)), 0.0);
  EXPECT_EQ(average_rate_hz(10, Duration::zero()), 0.0);
}

}  // namespace
}  // namespace mocaplink::core
