// Time bases of the messages we send (protocols/autopilots.md §4.3, docs/messages.md "Time").
//
// One rule: every time_usec / usec we send is the estimated *capture* time of the pose on the
// process's steady host clock (HostTime, the clock the adapters pass in), in microseconds. The
// mocap system stamps frames on its own clock (SourceTime); CaptureTimeMapper is the one place that
// turns a source capture time into a host capture time:
//
//   candidate(frame) = host receive time − source-reported latency (0 when the source reports none)
//                      − source capture time                      (the clocks' offset + transport)
//   drift            = slope of the minima of the latest complete windows (2 s each, up to 8),
//                      least squares, once there are 3; 0 before; at most ±kMaxSourceDrift
//   offset(t)        = minimum over the current and the previous window of
//                      (that window's minimum candidate + drift × (t − when it was seen))
//   host capture     = source capture + offset, clamped to be > the previous result and ≤ receive
//
// The minimum picks the least-delayed frames (network and scheduling delays are never negative),
// so jitter does not reach the timestamps, and a result never lies in the future — the same
// reasoning as ArduPilot's JitterCorrection (§4.2). A source clock that runs at another rate than
// the host's (a Vicon numbering frames at 100 Hz that come at 99.85 Hz: 1.5 ms/s; a crystal 100
// ppm off) moves the candidates steadily; the drift carries the older minimum to now, so the
// capture time does not fall behind by the windows' age (6 ms at 1.5 ms/s without it). A jump of
// more than `max_step` (source restarted, clock reset) re-seeds it.
//
// GPS time (GPS_INPUT time_week / time_week_ms) needs the wall clock, which the core never reads:
// the app passes one (host time, Unix time) pair (Bridge::set_wall_clock); GPS time of a host
// time t is then unix(t) converted with gps_time_from_unix_us. Thread-safety: not thread-safe
// (one owner); the free functions are pure.
#pragma once

#include <cstdint>
#include <optional>
#include <vector>

#include "mocaplink/core/time.hpp"

namespace mocaplink::core {

/// The most drift between a source clock and the host's that the mapper follows: 1 % (a frame
/// rate 1 % off its nominal). A larger slope is measurement noise or a restart in the making.
inline constexpr double kMaxSourceDrift = 0.01;

/// How far a source's clock may jump against the host's between two frames before it counts as a
/// clock that started again: the mapper re-seeds there, and core::source_clock_restarted (the
/// Bridge's and the recorder's rule) takes a leap ahead that large for a restart.
inline constexpr Duration kSourceClockLeap = std::chrono::seconds(1);

/// Maps source capture times to host capture times (see the file comment).
class CaptureTimeMapper {
 public:
  struct Config {
    Duration window = std::chrono::seconds(2);  ///< rotation period of the minimum; > 0
    Duration max_step = kSourceClockLeap;       ///< candidate jump that re-seeds; > 0
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
  /// Source clock drift against the host's followed now: d(host − source)/d(host), so +0.0015
  /// for a source whose clock runs 1500 ppm slow. 0 until three windows are complete.
  [[nodiscard]] double drift() const { return drift_; }

 private:
  struct Minimum {
    Duration candidate;
    HostTime seen;  ///< receive time of the frame that gave it
  };
  [[nodiscard]] Duration projected(const Minimum& m, HostTime t) const;
  void fit_drift();

  Config config_;
  std::optional<Duration> offset_;
  std::optional<Minimum> current_min_;
  std::vector<Minimum> minima_;  // complete windows, oldest first, at most kDriftWindows
  double drift_ = 0;
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
