// PosesFirst (issue 38): a forwarded frame goes out only where it cannot delay the next pose, with
// injected time and a modelled UART.
#include "mocaplink/io/poses_first.hpp"

#include <vector>

#include <gtest/gtest.h>

namespace mocaplink::io {
namespace {

using std::chrono::milliseconds;

const core::HostTime t0{std::chrono::seconds(10)};

std::vector<std::uint8_t> frame(std::size_t bytes, std::uint8_t tag = 0) {
  return std::vector<std::uint8_t>(bytes, tag);
}

TEST(PosesFirst, WithoutASpeedOnlyTheQueueRules) {
  PosesFirst gate({.bytes_per_second = 0.0, .max_queue_bytes = 100});
  core::HostTime retry{};
  EXPECT_FALSE(gate.next(t0, retry));
  EXPECT_TRUE(gate.push(frame(60, 1), t0));
  EXPECT_FALSE(gate.push(frame(60, 2), t0));  // 120 > 100: dropped, counted
  EXPECT_TRUE(gate.push(frame(40, 3), t0));
  EXPECT_EQ(gate.counters().dropped_full, 1u);
  gate.on_own_write(245, t0);
  const auto first = gate.next(t0, retry);
  ASSERT_TRUE(first);
  EXPECT_EQ(first->front(), 1);  // in order
  const auto second = gate.next(t0, retry);
  ASSERT_TRUE(second);
  EXPECT_EQ(second->front(), 3);
  EXPECT_TRUE(gate.empty());
  EXPECT_EQ(gate.counters().handed_out, 2u);
  EXPECT_EQ(gate.counters().bytes_handed_out, 100u);
  EXPECT_EQ(gate.counters().own_bytes, 245u);
}

// 57600 baud: 5760 bytes/s, so a 245-byte ODOMETRY takes 42.5 ms and a 57-byte frame 9.9 ms.
// Poses at 15 Hz (66.7 ms): the next is due 60 ms (a tenth of the period early) after the last.
class Serial57600 : public testing::Test {
 protected:
  Serial57600() { gate.set_pose_period(std::chrono::nanoseconds(66'666'667)); }
  PosesFirst gate{{.bytes_per_second = 5760.0, .max_queue_bytes = 4096}};
  core::HostTime retry{};
};

TEST_F(Serial57600, AFrameWaitsUntilThePoseHasLeftAndFitsBeforeTheNext) {
  gate.on_own_write(245, t0);  // the UART is busy until t0 + 42.5 ms
  ASSERT_TRUE(gate.push(frame(57), t0));
  // Now: done at 52.4 ms < due at 60 ms: it fits behind the pose.
  EXPECT_TRUE(gate.next(t0 + milliseconds(1), retry));
  // A second one would end at 62.3 ms: after the due pose, so it waits for the pose.
  ASSERT_TRUE(gate.push(frame(57), t0));
  EXPECT_FALSE(gate.next(t0 + milliseconds(2), retry));
  EXPECT_GE(retry, t0 + milliseconds(60));
  // The pose goes at 66 ms; the frame fits behind it.
  gate.on_own_write(245, t0 + milliseconds(66));
  EXPECT_TRUE(gate.next(t0 + milliseconds(67), retry));
}

TEST_F(Serial57600, AFrameTooLongForAnyGapWaitsWhilePosesFlowAndGoesWhenTheyStop) {
  gate.on_own_write(245, t0);
  ASSERT_TRUE(gate.push(frame(280), t0));  // 48.6 ms: 42.5 + 48.6 > 60 ms
  EXPECT_FALSE(gate.next(t0 + milliseconds(1), retry));
  gate.on_own_write(245, t0 + milliseconds(67));
  EXPECT_FALSE(gate.next(t0 + milliseconds(68), retry));
  // No pose for 1.5 periods (the mocap stopped): nothing is due, the queue flows.
  EXPECT_TRUE(gate.next(t0 + milliseconds(67 + 101), retry));
}

TEST_F(Serial57600, WithoutAPosePeriodTheUartModelAloneDecides) {
  PosesFirst plain({.bytes_per_second = 5760.0, .max_queue_bytes = 4096});
  plain.on_own_write(245, t0);
  ASSERT_TRUE(plain.push(frame(57), t0));
  EXPECT_TRUE(plain.next(t0, retry));  // no pose is known to be due
}

TEST_F(Serial57600, AFrameOlderThanMaxAgeIsDroppedNeverSent) {
  gate.on_own_write(245, t0);
  ASSERT_TRUE(gate.push(frame(280, 1), t0));  // too long for any gap while poses flow
  ASSERT_TRUE(gate.push(frame(20, 2), t0 + milliseconds(900)));
  for (int ms = 67; ms <= 1000; ms += 67) gate.on_own_write(245, t0 + milliseconds(ms));
  // 1.07 s later the first is stale: dropped, counted; the second is still young enough.
  gate.on_own_write(245, t0 + milliseconds(1072));
  const auto next = gate.next(t0 + milliseconds(1073), retry);
  EXPECT_EQ(gate.counters().dropped_stale, 1u);
  ASSERT_TRUE(next);
  EXPECT_EQ(next->front(), 2);
  EXPECT_TRUE(gate.empty());
}

TEST_F(Serial57600, AnOverloadedLinkDoesNotPushTheModelBeyondAFullQueue) {
  // Own traffic at four times the link's speed for 10 s, which a pty takes at once: the model
  // must stay within a full queue's air time (4096 B: 0.71 s) of now. Then poses at 15 Hz, which
  // fit: within 3 s the model has caught up and a ground station's frame goes between two poses
  // (without the bound it would wait for the 32 s the overload made up).
  for (int i = 0; i < 500; ++i) gate.on_own_write(490, t0 + milliseconds(20 * i));
  core::HostTime t = t0 + milliseconds(10'000);
  for (int i = 0; i < 45; ++i, t += milliseconds(67)) gate.on_own_write(245, t);
  gate.on_own_write(245, t);
  ASSERT_TRUE(gate.push(frame(57), t));
  EXPECT_TRUE(gate.next(t + milliseconds(1), retry));
}

TEST_F(Serial57600, WhatTheOsHoldsCanOnlyMakeTheLineBusierThanTheModel) {
  gate.on_own_write(245, t0);  // the model: busy until 42.5 ms
  ASSERT_TRUE(gate.push(frame(57), t0));
  // A pty says 0 while the line behind it still sends the pose: the model stands.
  gate.observe_unsent(0, t0 + milliseconds(1));
  ASSERT_TRUE(gate.next(t0 + milliseconds(1), retry));  // 42.5 + 9.9 < 60 ms: fits
  ASSERT_TRUE(gate.push(frame(57), t0 + milliseconds(2)));
  EXPECT_FALSE(gate.next(t0 + milliseconds(2), retry));  // behind both: 62 ms > 60
  // A real UART that says it still holds 200 bytes more than the model knew: later, not earlier.
  gate.on_own_write(245, t0 + milliseconds(66));
  gate.observe_unsent(245 + 200, t0 + milliseconds(66));
  EXPECT_FALSE(gate.next(t0 + milliseconds(67), retry));  // 66 + 77 + 10 > 126 ms
}

TEST_F(Serial57600, ClearDropsWhatWaits) {
  ASSERT_TRUE(gate.push(frame(57), t0));
  ASSERT_TRUE(gate.push(frame(57), t0));
  EXPECT_EQ(gate.queued_bytes(), 114u);
  EXPECT_EQ(gate.clear(), 2u);
  EXPECT_TRUE(gate.empty());
  EXPECT_EQ(gate.queued_bytes(), 0u);
}

}  // namespace
}  // namespace mocaplink::io
