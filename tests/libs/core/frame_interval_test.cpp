#include "mocaplink/core/frame_interval.hpp"

#include <gtest/gtest.h>

namespace mocaplink::core {
namespace {

using namespace std::chrono_literals;

const SourceTime s0 = source_time_from_ns(1'000'000'000'000);

/// A FrameInterval that observed `n` frames `step` apart, the first at `first`.
FrameInterval observed(Duration step, int n, SourceTime first = s0) {
  FrameInterval interval;
  for (int i = 0; i < n; ++i) interval.observe(first + i * step);
  return interval;
}

TEST(FrameInterval, NoneBeforeTwoFramesThenTheirInterval) {
  FrameInterval interval;
  EXPECT_FALSE(interval.value().has_value());
  EXPECT_FALSE(interval.last().has_value());
  interval.observe(s0);
  EXPECT_FALSE(interval.value().has_value());
  EXPECT_EQ(interval.last(), s0);
  interval.observe(s0 + 10ms);
  EXPECT_EQ(interval.value(), 10ms);
  EXPECT_EQ(interval.last(), s0 + 10ms);
}

TEST(FrameInterval, FallsAtOnceRisesBySixteenthsOfTheDifference) {
  FrameInterval interval = observed(10ms, 100);
  interval.observe(s0 + 99 * 10ms + 26ms);  // a longer gap: 10 + (26 - 10) / 16
  EXPECT_EQ(interval.value(), 11ms);
  interval.observe(*interval.last() + 4ms);  // a shorter one: at once
  EXPECT_EQ(interval.value(), 4ms);
}

TEST(FrameInterval, APauseOfTheSourceIsUndoneByTheNextFrame) {
  FrameInterval interval = observed(10ms, 100);
  interval.observe(s0 + 99 * 10ms + 1s);
  EXPECT_GT(interval.value(), 10ms);
  interval.observe(s0 + 99 * 10ms + 1s + 10ms);
  EXPECT_EQ(interval.value(), 10ms);
}

TEST(FrameInterval, ARepeatedOrEarlierCaptureTimeIsNoInterval) {
  // A Vicon UDP frame split over three datagrams comes three times with one capture time.
  FrameInterval split;
  for (int i = 0; i < 100; ++i) {
    for (int copy = 0; copy < 3; ++copy) split.observe(s0 + i * 10ms);
  }
  EXPECT_EQ(split.value(), 10ms);

  // The source's clock went back (it restarted): the next interval counts from there.
  FrameInterval restarted = observed(10ms, 100);
  restarted.observe(s0 - 5s);
  EXPECT_EQ(restarted.value(), 10ms);
  EXPECT_EQ(restarted.last(), s0 - 5s);
  restarted.observe(s0 - 5s + 4ms);
  EXPECT_EQ(restarted.value(), 4ms);
}

TEST(FrameInterval, FollowsASlowerRateWithinAFewDozenFrames) {
  FrameInterval interval = observed(std::chrono::microseconds(4167), 100);  // 240 Hz
  const SourceTime from = *interval.last();
  for (int i = 1; i <= 60; ++i) interval.observe(from + i * 10ms);  // then 100 Hz
  ASSERT_TRUE(interval.value().has_value());
  EXPECT_GT(*interval.value(), 9.5ms);
  EXPECT_LE(*interval.value(), 10ms);
}

}  // namespace
}  // namespace mocaplink::core
