// VehicleClockMonitor: how a vehicle's clock runs against the host's, measured from its own
// TIMESYNC requests, and whether PX4's time sync can be trusted with our capture times (issue 45).
//
// PX4 turns every ODOMETRY time_usec into its own time with `time_usec + offset`, where offset is
// the output of a double exponential filter over the samples our TIMESYNC answers give it, with
// gains of 0.003 once it has converged (500 samples, 50 s at its 10 Hz; protocols/autopilots.md
// §3.10). That filter follows a clock whose rate is constant, whatever the rate, but it takes
// minutes to follow a *change* of rate: against a clock whose rate wanders by a few thousand ppm
// its offset lags by tens of ms to 100 ms, and a lag one way puts every pose in PX4's future,
// where EKF2 stops fusing it. A flight controller's crystal runs within ~100 ppm of the host and
// changes rate only with temperature, slowly; a simulator's lockstep clock (PX4 SITL with SIH or
// Gazebo) runs as fast as the simulation manages, 0.5–3 % slow on a loaded machine and varying with
// the load. So the verdict:
//   measuring  fewer than `windows_for_verdict` complete windows since the vehicle's clock started
//   steady     the window minima lie on a line (within `max_residual`) whose rate is within
//              `max_rate_ppm` of the host's: PX4's filter follows it, capture times are safe
//   unsteady   otherwise; kept until the vehicle restarts (a clock that was unsteady once is a
//              simulator's, and a PX4 that converges again would be caught out at the next change)
//
// The measurement: each request carries the vehicle's send time (ts1); host arrival − ts1 is the
// clock offset plus the one-way delay, which is never negative. The minimum of each window (5 s,
// 50 requests) is the least-delayed request; a least-squares line through the latest windows'
// minima gives the rate, and the largest distance of a minimum from that line the residual. A
// request whose ts1 lies more than kVehicleClockRestartStep before the latest one is a reboot:
// the measurement starts again. Pure; time is passed in; not thread-safe (one owner).
#pragma once

#include <cstddef>
#include <cstdint>
#include <optional>
#include <string_view>
#include <vector>

#include "mocaplink/core/time.hpp"

namespace mocaplink::core {

enum class VehicleClockVerdict : std::uint8_t {
  measuring,  ///< not enough windows yet
  steady,     ///< a crystal's clock: PX4's time sync follows it
  unsteady,   ///< a rate off or changing: PX4's time sync would misplace poses
};
/// "measuring", "steady", "unsteady": the API's spellings (docs/api.md).
[[nodiscard]] std::string_view to_string(VehicleClockVerdict verdict);

/// A vehicle clock whose requests' ts1 goes back by more than this restarted (rebooted).
inline constexpr Duration kVehicleClockRestartStep = std::chrono::seconds(1);

struct VehicleClockConfig {
  Duration window = std::chrono::seconds(5);  ///< one minimum per window; > 0
  std::size_t windows_for_verdict = 4;        ///< complete windows before a verdict; ≥ 2
  std::size_t windows_kept = 12;  ///< windows in the fit (60 s); ≥ windows_for_verdict
  /// Steady only within this of the host's rate. Crystals are within ~100 ppm, and the host's own
  /// steady clock (CLOCK_MONOTONIC) may be slewed by NTP by up to 500 ppm (the kernel's limit);
  /// PX4's filter follows any constant rate, so the limit only has to tell those from a
  /// simulator's clock (0.5–3 % off under load).
  double max_rate_ppm = 1000.0;
  /// Steady only while every window minimum is within this of the fitted line: a rate that
  /// changed, or a clock that stalled, moves the minima off it.
  Duration max_residual = std::chrono::milliseconds(2);
};

/// What the dashboard shows.
struct VehicleClockFigures {
  VehicleClockVerdict verdict = VehicleClockVerdict::measuring;
  std::optional<double> rate_ppm;  ///< vehicle rate − host rate, ppm (+: the vehicle's is fast)
  std::optional<double> residual_ms;  ///< largest distance of a window minimum from the line
  std::size_t windows = 0;            ///< complete windows in the fit
  std::uint64_t requests = 0;         ///< requests measured since the vehicle's clock started
  std::uint64_t restarts = 0;         ///< reboots seen (ts1 went back, or restart())
};

class VehicleClockMonitor {
 public:
  VehicleClockMonitor() = default;
  explicit VehicleClockMonitor(VehicleClockConfig config) : config_(config) {}

  /// A TIMESYNC request stamped `ts1_ns` on the vehicle's clock arrived at `arrival`. Returns
  /// true when the verdict changed (a restart back to measuring included).
  bool on_request(std::int64_t ts1_ns, HostTime arrival);
  /// The vehicle rebooted (its ts1 went back, or seen elsewhere: its boot clock went back):
  /// measure afresh, counted in `restarts`.
  void restart();

  [[nodiscard]] VehicleClockVerdict verdict() const noexcept { return figures_.verdict; }
  [[nodiscard]] const VehicleClockFigures& figures() const noexcept { return figures_; }

 private:
  struct Minimum {
    HostTime at;
    std::int64_t host_minus_vehicle_ns;
  };
  void close_window();
  void fit();

  VehicleClockConfig config_;
  VehicleClockFigures figures_;
  std::vector<Minimum> minima_;           // complete windows, oldest first, ≤ windows_kept
  std::optional<Minimum> current_;        // the open window's minimum
  std::optional<HostTime> window_start_;  // of the open window
  std::optional<std::int64_t> last_ts1_ns_;
};

}  // namespace mocaplink::core
