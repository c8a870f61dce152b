#include "mocaplink/core/late_frames.hpp"

#include <gtest/gtest.h>

namespace mocaplink::core {
namespace {

using namespace std::chrono_literals;

const HostTime t0{std::chrono::seconds(1000)};

/// A LateFrames whose loop is behind: it took a frame that had waited longer than kCatchUpAfter.
LateFrames behind_loop() {
  LateFrames late;
  late.begin_batch(t0 - kCatchUpAfter - 1ms, t0);
  return late;
}

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

MocapFrame frame_of(std::uint64_t number, std::initializer_list<const char*> names) {
  MocapFrame frame;
  frame.frame_number = number;
  for (const char* name : names) frame.bodies.push_back(BodySample{name, true, {}, {}});
  return frame;
}

TEST(Supersedes, ANewerFrameWithEveryBodyOfTheOlderOne) {
  const auto older = frame_of(1, {"Quad1", "Quad2"});
  EXPECT_TRUE(supersedes(frame_of(2, {"Quad1", "Quad2"}), older));
  EXPECT_TRUE(supersedes(frame_of(2, {"Quad2", "Quad1"}), older));           // any order
  EXPECT_TRUE(supersedes(frame_of(2, {"Quad1", "Quad2", "Rover"}), older));  // and more
  EXPECT_TRUE(supersedes(frame_of(2, {"Rover", "Quad2", "Quad1"}), older));
  auto untracked = frame_of(2, {"Quad1", "Quad2"});
  untracked.bodies[1].tracked = false;  // the newer word on Quad2 (lost) is the one that counts
  EXPECT_TRUE(supersedes(untracked, older));
  EXPECT_TRUE(supersedes(frame_of(2, {}), frame_of(1, {})));
}

TEST(Supersedes, NotAFrameThatLacksOneOfItsBodies) {
  const auto older = frame_of(1, {"Quad1", "Quad2"});
  EXPECT_FALSE(supersedes(frame_of(2, {"Quad1"}), older));  // a source that splits its bodies
  EXPECT_FALSE(supersedes(frame_of(2, {"Quad2"}), older));
  EXPECT_FALSE(supersedes(frame_of(2, {"Quad1", "Rover"}), older));
  EXPECT_FALSE(supersedes(frame_of(2, {}), older));
  EXPECT_FALSE(supersedes(frame_of(2, {"quad1", "Quad2"}), older));  // names are exact
}

TEST(LateFrames, AFrameIsSupersededOnlyByANewerOneWaitingWithAllItsBodies) {
  LateFrames late = behind_loop();
  const auto first = frame_of(1, {"Quad1", "Quad2"});
  const auto second = frame_of(2, {"Quad1", "Quad2"});
  const auto partial = frame_of(3, {"Quad1"});
  const HostTime later = t0 + 4ms;  // a frame period at 240 Hz after the first arrived
  EXPECT_FALSE(late.skip_if_superseded(first, t0, partial, later));
  EXPECT_EQ(late.superseded(), 0u);
  EXPECT_TRUE(late.skip_if_superseded(first, t0, second, later));
  EXPECT_TRUE(late.skip_if_superseded(partial, t0, second, later));
  EXPECT_EQ(late.superseded(), 2u);
  EXPECT_EQ(late.skipped(), 0u);  // counted apart from the late ones
}

TEST(LateFrames, FramesOfOneBurstDoNotSupersedeEachOther) {
  // Frames that arrived together (a TCP read of two frames, a VRPN round, a replay catching up)
  // reached the loop together however idle it was: each is sent (or judged late by its capture).
  LateFrames late = behind_loop();
  const auto first = frame_of(1, {"Quad1"});
  const auto second = frame_of(2, {"Quad1"});
  EXPECT_FALSE(late.skip_if_superseded(first, t0, second, t0));
  EXPECT_FALSE(late.skip_if_superseded(first, t0, second, t0 + 20us));
  EXPECT_FALSE(late.skip_if_superseded(first, t0, second, t0 + kSameBurst));  // the limit: a burst
  EXPECT_EQ(late.superseded(), 0u);
  EXPECT_TRUE(late.skip_if_superseded(first, t0, second, t0 + kSameBurst + 1ns));
  EXPECT_TRUE(late.skip_if_superseded(first, t0, second, t0 + 1ms));  // 1000 Hz, the loop behind
  EXPECT_EQ(late.superseded(), 2u);
}

TEST(LateFrames, NothingIsSupersededWhileTheLoopIsLessThanTheLimitBehind) {
  // A hiccup: the loop took a batch a little late, the older frame waited 9 ms, a newer one 5 ms.
  // Both are sent, a few ms late, as on a loop that never supersedes.
  LateFrames late;
  const auto first = frame_of(1, {"Quad1"});
  const auto second = frame_of(2, {"Quad1"});
  late.begin_batch(t0, t0 + 9ms);
  EXPECT_FALSE(late.behind());
  EXPECT_FALSE(late.skip_if_superseded(first, t0, second, t0 + 4ms));
  late.begin_batch(t0, t0 + kCatchUpAfter);  // exactly the limit: not yet behind
  EXPECT_FALSE(late.skip_if_superseded(first, t0, second, t0 + 4ms));
  EXPECT_EQ(late.superseded(), 0u);
  late.begin_batch(t0, t0 + kCatchUpAfter + 1ns);
  EXPECT_TRUE(late.behind());
  EXPECT_TRUE(late.skip_if_superseded(first, t0, second, t0 + 4ms));
  EXPECT_EQ(late.superseded(), 1u);
}

TEST(LateFrames, TheLoopStaysBehindUntilAFrameFindsItIdle) {
  LateFrames late;
  const auto first = frame_of(1, {"Quad1"});
  const auto second = frame_of(2, {"Quad1"});
  late.begin_batch(t0, t0 + 20ms);  // a frame waited 20 ms: behind
  late.end_batch(t0 + 25ms);
  // The next batch's oldest frame came at t0 + 24 ms, while the loop was busy with the batch
  // before: the loop is still behind, although that frame waited only 1 ms.
  late.begin_batch(t0 + 24ms, t0 + 25ms);
  EXPECT_TRUE(late.behind());
  EXPECT_TRUE(late.skip_if_superseded(first, t0 + 24ms, second, t0 + 25ms));
  late.end_batch(t0 + 28ms);
  // This one came at t0 + 29 ms, after the loop was done at t0 + 28 ms: it found the loop idle.
  late.begin_batch(t0 + 29ms, t0 + 29ms);
  EXPECT_FALSE(late.behind());
  EXPECT_FALSE(late.skip_if_superseded(first, t0 + 29ms, second, t0 + 33ms));
  late.end_batch(t0 + 30ms);
  late.begin_batch(t0 + 30ms, t0 + 30ms + kCatchUpAfter + 1ms);  // waited 11 ms: behind again
  EXPECT_TRUE(late.behind());
  late.end_batch(t0 + 45ms);
  // Handed over exactly when the loop was done counts as busy (it was in the queue as the loop
  // finished): still behind, although it waited only 1 ms.
  late.begin_batch(t0 + 45ms, t0 + 46ms);
  EXPECT_TRUE(late.behind());
  late.end_batch(t0 + 47ms);
  late.begin_batch(t0 + 48ms, t0 + 48ms);  // idle: caught up
  EXPECT_FALSE(late.behind());
  late.end_batch(t0 + 49ms);
  // Handed over after the loop was done, so it found the loop idle, but the loop then took 15 ms
  // to get to it (other work: a tick, the dashboard): late is late, the loop is behind.
  late.begin_batch(t0 + 50ms, t0 + 65ms);
  EXPECT_TRUE(late.behind());
  EXPECT_EQ(late.superseded(), 1u);
}

/// A LateFrames whose loop took `n` frames captured `period` apart.
LateFrames took_every(Duration period, int n) {
  LateFrames late;
  MocapFrame frame;
  for (int i = 0; i < n; ++i) {
    frame.frame_number = static_cast<std::uint64_t>(i);
    frame.capture_time = source_time_from_ns(1'000'000'000'000) + i * period;
    late.observe(frame);
  }
  return late;
}

TEST(LateFrames, BelowTwoHundredHertzTheLoopIsBehindOnlyOnceAFrameWaitedTwoPeriods) {
  // 240 Hz: two periods are 8.3 ms, so the limit stays 10 ms.
  LateFrames fast = took_every(std::chrono::microseconds(4167), 100);
  EXPECT_EQ(fast.catch_up_after(), kCatchUpAfter);
  fast.begin_batch(t0, t0 + 11ms);
  EXPECT_TRUE(fast.behind());

  // 100 Hz: a loop one frame late (a frame waited 15 ms) is not behind; two frames late is.
  LateFrames slow = took_every(10ms, 100);
  EXPECT_EQ(slow.catch_up_after(), 20ms);
  slow.begin_batch(t0, t0 + 15ms);
  EXPECT_FALSE(slow.behind());
  EXPECT_FALSE(
      slow.skip_if_superseded(frame_of(1, {"Quad1"}), t0, frame_of(2, {"Quad1"}), t0 + 10ms));
  slow.begin_batch(t0, t0 + 20ms);  // exactly two periods: not yet
  EXPECT_FALSE(slow.behind());
  slow.begin_batch(t0, t0 + 20ms + 1ns);
  EXPECT_TRUE(slow.behind());

  // 10 Hz would be 200 ms: the limit stops at kMaxCatchUpAfter.
  EXPECT_EQ(took_every(100ms, 100).catch_up_after(), kMaxCatchUpAfter);
}

TEST(LateFrames, TheLimitFollowsTheFramesTheLoopTook) {
  // Before two frames, kCatchUpAfter.
  EXPECT_EQ(LateFrames().catch_up_after(), kCatchUpAfter);
  EXPECT_EQ(took_every(10ms, 1).catch_up_after(), kCatchUpAfter);
  // A Vicon UDP frame split over three datagrams is taken three times, with one capture time:
  // the period is the frames' 10 ms, not a third of it (which would keep the limit at 10 ms).
  LateFrames late;
  MocapFrame frame;
  for (int i = 0; i < 100; ++i) {
    frame.capture_time = source_time_from_ns(1'000'000'000'000) + i * 10ms;
    for (int copy = 0; copy < 3; ++copy) late.observe(frame);
  }
  EXPECT_EQ(late.catch_up_after(), 20ms);
}

TEST(LateFrames, TheWarningSaysHowManyWereSupersededAndHowManyLate) {
  LateFrames late = behind_loop();
  const auto first = frame_of(1, {"Quad1"});
  const auto second = frame_of(2, {"Quad1"});
  ASSERT_TRUE(late.skip_if_superseded(first, t0, second, t0 + 4ms));
  const auto warned = late.warning(t0);  // superseded alone is warned about, at once
  ASSERT_TRUE(warned.has_value());
  EXPECT_EQ(warned->superseded, 1u);
  EXPECT_EQ(warned->skipped, 0u);

  // Within the period both kinds are held back, then given together.
  ASSERT_TRUE(late.skip_if_superseded(first, t0, second, t0 + 4ms));
  ASSERT_TRUE(late.skip_if_superseded(first, t0, second, t0 + 4ms));
  ASSERT_TRUE(late.skip_if_late(t0 + 1s, t0 + 1s + 300ms));
  EXPECT_FALSE(late.warning(t0 + 2s).has_value());
  const auto next = late.warning(t0 + kLateWarningPeriod);
  ASSERT_TRUE(next.has_value());
  EXPECT_EQ(next->superseded, 2u);
  EXPECT_EQ(next->skipped, 1u);
  EXPECT_EQ(next->oldest, 300ms);
  EXPECT_EQ(late.superseded(), 3u);
  EXPECT_EQ(late.skipped(), 1u);
}

}  // namespace
}  // namespace mocaplink::core
