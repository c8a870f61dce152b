// DdsTimeSyncCheck: whether a PX4 reached over uXRCE-DDS converts mocaplink's capture times to the
// right moment of its own clock, and so which stamps its poses should carry (issue 47; ros2-dds.md
// §4; PX4 v1.14.3's generated uORB/ucdr/*.h).
//
// PX4's client keeps one estimate of the Agent host's clock against its own (its XRCE time sync)
// and uses it both ways: what it sends is stamped `t_px4 + offset`, what it receives is converted
// `min(t − offset, now)`, and a stamp of 0 is replaced by its arrival. With the estimate off by ε
// (estimate − truth), a sample PX4 sends arrives here, on the Agent's host, `transport − ε` after
// its stamp, and a capture time we send lands ε earlier in PX4's time than it happened: ε > 0 puts
// our poses in its past (EKF2 fuses them that much too early, or drops them once they are older
// than its buffer: seen in PX4 SITL, whose lockstep clock drifts against the wall clock, with ε of
// 30–110 ms), ε < 0 in its future, which PX4 clamps to their arrival. So the least of (arrival −
// stamp) over a window of PX4's samples is −ε plus the least transport (under a millisecond on one
// host).
//
// The verdict, judged each kDdsSyncWindow from that least difference m:
//   capture  the last kDdsSyncGoodWindows windows each had samples and |m| ≤ kDdsSyncToleranceMs:
//            send the capture time (PX4 places the pose where it happened; EKF2_EV_DELAY 0);
//   arrival  otherwise, from the start: send 0, so PX4 stamps each pose on its arrival, never in
//            its past, and EKF2_EV_DELAY covers the delay — what the MAVLink path does when it
//            withholds TIMESYNC from an unsteady clock (vehicle_state.hpp).
// A window with m beyond the tolerance turns capture into arrival at once; a gap without samples
// longer than a window starts again from arrival (the vehicle restarted, or its sync with it).
// Samples stamped below kWallClockStampUs carry PX4's boot time (its sync not running): they
// count as beyond the tolerance. Pure; not thread-safe.
#pragma once

#include <cstdint>
#include <optional>
#include <string>
#include <string_view>

#include "mocaplink/core/time.hpp"

namespace mocaplink::core {

inline constexpr Duration kDdsSyncWindow = std::chrono::seconds(1);
inline constexpr int kDdsSyncGoodWindows = 5;
inline constexpr double kDdsSyncToleranceMs = 5.0;
/// A stamp at or above this (µs) is on a wall clock (after 2001), below it PX4's boot time.
inline constexpr std::uint64_t kWallClockStampUs = 1'000'000'000'000'000ULL;

enum class DdsPoseStamps : std::uint8_t {
  arrival,  ///< timestamp_sample 0: PX4 stamps the pose when it arrives
  capture,  ///< timestamp_sample the capture time on this host's wall clock
};
/// "arrival", "capture" (the API's `clock.pose_stamps`).
[[nodiscard]] std::string_view to_string(DdsPoseStamps stamps);

class DdsTimeSyncCheck {
 public:
  /// A sample of PX4's stamped `stamp_us` (its `timestamp`, µs) arrived at `arrival_unix_us` on
  /// this host's wall clock, at host time `now`. True when the verdict changed.
  bool on_sample(std::uint64_t stamp_us, std::int64_t arrival_unix_us, HostTime now);

  [[nodiscard]] DdsPoseStamps stamps() const noexcept { return stamps_; }
  /// ε as the latest complete window measured it (ms, PX4's estimate − truth: > 0 puts capture
  /// times in its past); nullopt before one, or when PX4 stamped its boot time.
  [[nodiscard]] std::optional<double> error_ms() const noexcept { return error_ms_; }
  /// The sentence of the log and the dashboard.
  [[nodiscard]] std::string text() const;

 private:
  void close_window(HostTime now);

  DdsPoseStamps stamps_ = DdsPoseStamps::arrival;
  std::optional<HostTime> window_start_;
  std::optional<HostTime> last_sample_;
  std::optional<std::int64_t> window_min_us_;  ///< least arrival − stamp this window
  bool window_boot_stamps_ = false;            ///< a sample this window carried boot time
  int good_windows_ = 0;
  std::optional<double> error_ms_;
};

}  // namespace mocaplink::core
