// 32-bit targets (armhf): no time value or counter of mocaplink may be narrower than 64 bits, and
// dates after 2038-01-19 (where a 32-bit time_t ends) must convert exactly. Expected values were
// computed independently (Python's datetime, UTC) and are written here as literals.
#include <gtest/gtest.h>

#include <chrono>
#include <cstdint>
#include <limits>
#include <type_traits>

#include "mocaplink/core/mocap_frame.hpp"
#include "mocaplink/core/sender_clock.hpp"
#include "mocaplink/core/time.hpp"
#include "mocaplink/core/vehicle_state.hpp"
#include "mocaplink/io/clock.hpp"
#include "mocaplink/mavlink/signing.hpp"

namespace {

using namespace mocaplink;

template <typename T>
constexpr bool is_64_bit = std::numeric_limits<T>::digits >= 63;

// 2040-02-29 12:00:00 UTC, after the 32-bit time_t limit (2038-01-19 03:14:07 UTC).
constexpr std::int64_t kAfter2038UnixS = 2'214'129'600;

TEST(Platform, ClockCountsAre64Bit) {
  static_assert(is_64_bit<std::chrono::system_clock::rep>);
  static_assert(is_64_bit<std::chrono::steady_clock::rep>);
  static_assert(is_64_bit<core::HostTime::rep>);
  static_assert(is_64_bit<decltype(io::unix_now_us())>);
  static_assert(is_64_bit<decltype(io::signing_now_10us())>);
  // The wall clock read through the io adapter is after 2024 (µs since 1970 > 1.7e15), which a
  // 32-bit count of µs, ms or s since 1970 could not hold.
  EXPECT_GT(io::unix_now_us(), std::int64_t{1'700'000'000} * 1'000'000);
  EXPECT_GT(io::signing_now_10us(), std::uint64_t{0});
}

TEST(Platform, SigningTimestampAfter2038) {
  // (2214129600 - 1420070400) s in 10 µs units.
  EXPECT_EQ(mavlink::signing_timestamp_from_unix_us(kAfter2038UnixS * 1'000'000),
            std::uint64_t{79'405'920'000'000});
  // The signer keeps it exactly (48 bits hold ~89 years from 2015).
  mavlink::OutgoingSigner signer(mavlink::SigningKey({}), 1, 0);
  EXPECT_EQ(signer.next(79'405'920'000'000).timestamp_10us, std::uint64_t{79'405'920'000'000});
}

TEST(Platform, GpsTimeAfter2038) {
  // GPS time = Unix + 18 leap seconds - 315964800: week 3138, 302418000 ms into it.
  const auto gps = core::gps_time_from_unix_us(kAfter2038UnixS * 1'000'000);
  ASSERT_TRUE(gps.has_value());
  EXPECT_EQ(gps->week, 3138);
  EXPECT_EQ(gps->week_ms, 302'418'000u);
}

TEST(Platform, HostTimeMicrosecondsBeyond32Bits) {
  // 100 days of steady clock in µs (8.64e12) does not fit 32 bits.
  const auto t = core::host_time_from_ns(std::int64_t{100} * 86'400 * 1'000'000'000);
  EXPECT_EQ(core::host_time_usec(t), std::uint64_t{8'640'000'000'000});
}

TEST(Platform, CountersAre64Bit) {
  static_assert(is_64_bit<decltype(core::MocapFrame{}.frame_number)>);
  static_assert(is_64_bit<decltype(core::VehicleCounters{}.messages)>);
  static_assert(is_64_bit<decltype(core::VehicleCounters{}.heartbeats)>);
  core::MocapFrame frame;
  frame.frame_number = (std::uint64_t{1} << 32) + 5;  // past a 32-bit counter's wrap
  EXPECT_EQ(frame.frame_number, 4'294'967'301u);
}

}  // namespace
