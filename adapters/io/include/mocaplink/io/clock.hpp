// The process's clocks, read only here (libs/ never read a clock; DESIGN.md "Conventions").
//
//   host_now()          steady clock → core::HostTime: every timestamp handed to the core.
//   unix_now_us()       wall clock, µs since 1970: log files (.tlog records), never for control.
//   unix_ns_of(t)       a host time on the wall clock, ns since 1970 (the offset read now): the
//                       capture stamps of ROS 2 messages, whose time is the wall clock.
//   signing_now_10us()  wall clock in MAVLink signing units (10 µs since 2015-01-01 UTC,
//                       mavlink-wire.md §7.1): signing timestamps must follow real time so that
//                       a restarted bridge, or another signer of the same link, stays comparable.
// Thread-safety: all functions are thread-safe.
#pragma once

#include <cstdint>

#include "mocaplink/core/time.hpp"

namespace mocaplink::io {

/// std::chrono::steady_clock now, as HostTime (ns since an unspecified epoch, never jumps).
[[nodiscard]] core::HostTime host_now() noexcept;

/// std::chrono::system_clock now, µs since the Unix epoch (may jump when the clock is set).
[[nodiscard]] std::int64_t unix_now_us() noexcept;
/// `t` (a host_now() time) on the wall clock, ns since the Unix epoch: the clocks' offset is read
/// at each call, so a step of the wall clock (NTP) is followed from the next call on.
[[nodiscard]] std::int64_t unix_ns_of(core::HostTime t) noexcept;

/// The wall clock as a 48-bit MAVLink signing timestamp (10 µs units since 2015-01-01 UTC).
[[nodiscard]] std::uint64_t signing_now_10us() noexcept;

}  // namespace mocaplink::io
