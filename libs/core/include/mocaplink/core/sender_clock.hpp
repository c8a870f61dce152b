// Time bases of the messages we send (protocols/autopilots.md §4.3, docs/messages.md "Time").
//
// One rule: every time_usec / usec we send is the estimated *capture* time of the pose on the
// process's steady host clock (HostTime, the clock the adapters pass in), in microseconds. The
// mocap system stamps frames on its own clock (SourceTime); CaptureTimeMapper is the one place that
// turns a source capture time into a host capture time:
//
//   candidate(frame) = host receive time − source-reported latency (0 when the source reports none)
//                      − source capture time                      (the clocks' offset + transport)
//   offset           = minimum candidate over the current and the previous window (2 s each)
//   host capture     = source capture + offset, clamped to be > the previous result and ≤ receive
//
// The minimum picks the least-delayed frames (network and scheduling delays are never negative),
// so jitter does not reach the timestamps, and a result never lies in the future — the same
// reasoning as ArduPilot's JitterCorrection (§4.2). Windows rotate so that a slowly drifting source
// clock is followed; a jump of more than `max_step` (source restarted, clock reset) re-seeds it.
//
// GPS time (GPS_INPUT time_week / time_week_ms) needs the wall clock, which the core never reads:
// the app passes one (host time, Unix time) pair (Bridge::set_wall_clock); GPS time of a host
// time t is then unix(t) converted with gps_time_from_unix_us. Thread-safety: not thread-safe
// (one owner); the free functions are pure.
#pragma once

#include <cstdint>
#include <optional>

#include "mocaplink/core/time.hpp"

namespace mocaplink::core {

/// Maps source capture times to host capture times (see the file comment).
class CaptureTimeMapper {
 public:
  struct Config {
    Duration window = std::chrono::seconds(2);    ///< rotation period of the minimum; > 0
    Duration max_step = std::chrono::seconds(1);  ///< candidate jump that re-seeds; > 0
  };
  CaptureTimeMapper() = default;
  explicit CaptureTimeMapper(Config config) : config_(config) {}

  /// A frame captured at `capture` (source clock) was received at `received`, the source
  /// reporting `latency` (nullopt = none). Returns the frame's host capture time.
  HostTime on_frame(SourceTime capture, HostTime received, std::optional<Duration> latency);

  /// Host time of a source time with the current offset (no clamping); nullopt before the first
  /// frame.
  [[nodiscard]] std::optional<HostTime> to_host(SourceTime capture) const;
  /// Current offset host − source (nullopt before the first frame).
  [[nodiscard]] std::optional<Duration> offset() const { return offset_; }
  /// Times the offset was re-seeded after a jump (source restart), for the dashboard.
  [[nodiscard]] std::uint64_t reseeds() const { return reseeds_; }

 private:
  Config config_;
  std::optional<Duration> offset_;
  std::optional<Duration> current_min_;
  std::optional<Duration> previous_min_;
  HostTime window_start_{};
  std::optional<HostTime> last_result_;
  std::uint64_t reseeds_ = 0;
};

/// Microseconds of a host time (time_usec fields): floor(ns / 1000); 0 for times before the
/// clock's epoch (never produced by a steady clock).
[[nodiscard]] std::uint64_t host_time_usec(HostTime t);

/// GPS week and time of week (GPS_INPUT time_week, time_week_ms).
struct GpsTime {
  std::uint16_t week = 0;     ///< weeks since 1980-01-06 00:00:00 UTC (GPS epoch)
  std::uint32_t week_ms = 0;  ///< ms since the start of that week, [0, 604 800 000)
};

/// GPS − UTC in seconds: 18 leap seconds since 2017-01-01 (IERS Bulletin C; no leap second has
/// been announced since). Update here if one is.
inline constexpr std::int64_t kGpsLeapSeconds = 18;
/// Unix time of the GPS epoch 1980-01-06 00:00:00 UTC, seconds.
inline constexpr std::int64_t kGpsEpochUnixS = 315'964'800;

/// GPS time of a Unix time (µs since 1970-01-01 UTC): gps_s = unix_s − 315 964 800 + 18. nullopt
/// before the GPS epoch or when the week does not fit 16 bits (year 2236).
[[nodiscard]] std::optional<GpsTime> gps_time_from_unix_us(std::int64_t unix_us);

}  // namespace mocaplink::core
