// ClientSlots (connections per client address) and RequestDeadline (a whole request's time to
// arrive), with time passed in: the rules the dashboard server applies to its sockets (issue 15).
#include "mocaplink/web/connection_limits.hpp"

#include <gtest/gtest.h>

namespace mocaplink::web {
namespace {

using std::chrono::milliseconds;

TEST(ClientSlots, RefusesAnAddressOverItsCapAndCountsIt) {
  ClientSlots slots(2);
  EXPECT_TRUE(slots.try_acquire("127.0.0.1"));
  EXPECT_TRUE(slots.try_acquire("127.0.0.1"));
  EXPECT_FALSE(slots.try_acquire("127.0.0.1"));
  EXPECT_FALSE(slots.try_acquire("127.0.0.1"));
  EXPECT_EQ(slots.refused(), 2U);
  EXPECT_EQ(slots.open(), 2U);
}

TEST(ClientSlots, OtherAddressesAreNotAffected) {
  ClientSlots slots(1);
  EXPECT_TRUE(slots.try_acquire("127.0.0.1"));
  EXPECT_FALSE(slots.try_acquire("127.0.0.1"));
  EXPECT_TRUE(slots.try_acquire("127.0.0.2"));
  EXPECT_TRUE(slots.try_acquire("::1"));
  EXPECT_EQ(slots.open(), 3U);
  EXPECT_EQ(slots.refused(), 1U);
}

TEST(ClientSlots, AReleasedSlotCanBeTakenAgain) {
  ClientSlots slots(1);
  EXPECT_TRUE(slots.try_acquire("192.168.1.7"));
  slots.release("192.168.1.7");
  EXPECT_EQ(slots.open(), 0U);
  EXPECT_TRUE(slots.try_acquire("192.168.1.7"));
  EXPECT_EQ(slots.refused(), 0U);
}

class RequestDeadlineTest : public ::testing::Test {
 protected:
  const RequestDeadline::Clock::time_point t0_ =
      RequestDeadline::Clock::time_point{} + std::chrono::hours(1);
};

TEST_F(RequestDeadlineTest, WaitsAtMostTheSilenceLimitWhileTimeIsLeft) {
  RequestDeadline deadline(milliseconds(5000), milliseconds(2000));
  deadline.start(t0_);
  EXPECT_EQ(deadline.next_wait(t0_), milliseconds(2000));
  EXPECT_EQ(deadline.next_wait(t0_ + milliseconds(2500)), milliseconds(2000));
}

TEST_F(RequestDeadlineTest, WaitsOnlyForWhatIsLeftNearTheEnd) {
  RequestDeadline deadline(milliseconds(5000), milliseconds(2000));
  deadline.start(t0_);
  EXPECT_EQ(deadline.next_wait(t0_ + milliseconds(3500)), milliseconds(1500));
  // Less than a millisecond left still waits (rounded up), rather than spinning.
  EXPECT_EQ(deadline.next_wait(t0_ + std::chrono::microseconds(4999500)), milliseconds(1));
}

TEST_F(RequestDeadlineTest, ASlowClientRunsOutOfTheTotal) {
  // One byte a second: never silent for 2 s, but the request is not complete after 5 s.
  RequestDeadline deadline(milliseconds(5000), milliseconds(2000));
  deadline.start(t0_);
  for (int second = 0; second < 5; ++second) {
    EXPECT_TRUE(deadline.next_wait(t0_ + std::chrono::seconds(second)).has_value()) << second;
  }
  EXPECT_FALSE(deadline.next_wait(t0_ + std::chrono::seconds(5)).has_value());
  EXPECT_FALSE(deadline.next_wait(t0_ + std::chrono::seconds(60)).has_value());
}

TEST_F(RequestDeadlineTest, EachRequestStartsItsOwnDeadline) {
  RequestDeadline deadline(milliseconds(1000), milliseconds(2000));
  deadline.start(t0_);
  EXPECT_FALSE(deadline.next_wait(t0_ + milliseconds(1000)).has_value());
  deadline.start(t0_ + milliseconds(1200));
  EXPECT_EQ(deadline.next_wait(t0_ + milliseconds(1200)), milliseconds(1000));
}

}  // namespace
}  // namespace mocaplink::web
