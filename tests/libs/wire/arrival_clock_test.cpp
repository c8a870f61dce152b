// ArrivalClock (wire/arrival_clock.hpp) with injected times: frames received in a burst keep the
// source's spacing, the clock follows arrival slowly, and snaps to it after a silence.
#include "mocaplink/wire/arrival_clock.hpp"

#include <gtest/gtest.h>

namespace mocaplink::wire {
namespace {

using std::chrono::milliseconds;

core::HostTime at_ms(double ms) {
  return core::host_time_from_ns(static_cast<std::int64_t>(ms * 1e6));
}
double ms_of(core::SourceTime t) {
  return static_cast<double>(t.time_since_epoch().count()) / 1e6;
}

TEST(ArrivalClock, BurstKeepsTheSourceSpacing) {
  ArrivalClock c;
  EXPECT_DOUBLE_EQ(ms_of(c.next(at_ms(100), std::nullopt)), 100.0);
  EXPECT_DOUBLE_EQ(ms_of(c.next(at_ms(105), milliseconds(5))), 105.0);
  // Three frames 5 ms apart by the source, received together at 125 ms.
  const double a = ms_of(c.next(at_ms(125), milliseconds(5)));
  const double b = ms_of(c.next(at_ms(125), milliseconds(5)));
  const double d = ms_of(c.next(at_ms(125), milliseconds(5)));
  EXPECT_NEAR(a, 110.0 + 15.0 / 32, 1e-6);
  EXPECT_GT(b - a, 4.5);
  EXPECT_GT(d - b, 4.5);
}

TEST(ArrivalClock, SnapsToArrivalWithoutAStepOrAfterASilence) {
  ArrivalClock c;
  (void)c.next(at_ms(0), std::nullopt);
  EXPECT_DOUBLE_EQ(ms_of(c.next(at_ms(2000), milliseconds(5))), 2000.0);  // 0.5 s off: snap
  EXPECT_DOUBLE_EQ(ms_of(c.next(at_ms(2010), std::nullopt)), 2010.0);
  EXPECT_DOUBLE_EQ(ms_of(c.next(at_ms(2020), milliseconds(0))), 2020.0);  // no step
  EXPECT_DOUBLE_EQ(ms_of(c.next(at_ms(2030), milliseconds(5000))), 2030.0);
  // Never backwards, never equal.
  const auto t = c.next(at_ms(1000), std::nullopt);
  EXPECT_GT(ms_of(t), 2030.0);
}

}  // namespace
}  // namespace mocaplink::wire
