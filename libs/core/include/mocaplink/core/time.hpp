// Three clocks, three types (DESIGN.md "Conventions").
//
//   SourceTime  — capture time on the mocap system's clock (frame timestamps, latency samples).
//   HostTime    — this machine's steady clock, as passed in by the adapters; the core never reads
//                 a clock itself, so every behaviour is testable with injected time.
//   VehicleTime — the vehicle's boot clock, estimated from TIMESYNC.
//
// The clock types below have no now(): they only tag time points so the three domains cannot be
// mixed by accident. Resolution is 1 ns throughout; durations are std::chrono::nanoseconds.
#pragma once

#include <chrono>
#include <cstdint>

namespace mocaplink::core {

struct SourceClock {
  using rep = std::int64_t;
  using period = std::nano;
  using duration = std::chrono::nanoseconds;
  using time_point = std::chrono::time_point<SourceClock, duration>;
  static constexpr bool is_steady = true;
};

struct HostClock {
  using rep = std::int64_t;
  using period = std::nano;
  using duration = std::chrono::nanoseconds;
  using time_point = std::chrono::time_point<HostClock, duration>;
  static constexpr bool is_steady = true;
};

struct VehicleClock {
  using rep = std::int64_t;
  using period = std::nano;
  using duration = std::chrono::nanoseconds;
  using time_point = std::chrono::time_point<VehicleClock, duration>;
  static constexpr bool is_steady = true;
};

using SourceTime = SourceClock::time_point;
using HostTime = HostClock::time_point;
using VehicleTime = VehicleClock::time_point;
using Duration = std::chrono::nanoseconds;

/// Seconds as double, for filters and rates. Exact for |d| < 2^53 ns (~104 days).
constexpr double to_seconds(Duration d) {
  return std::chrono::duration<double>(d).count();
}

/// Host time from a raw nanosecond count (adapters convert std::chrono::steady_clock here).
constexpr HostTime host_time_from_ns(std::int64_t ns) {
  return HostTime{Duration{ns}};
}

/// Source time from a raw nanosecond count.
constexpr SourceTime source_time_from_ns(std::int64_t ns) {
  return SourceTime{Duration{ns}};
}

}  // namespace mocaplink::core
