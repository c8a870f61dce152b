// Glue from the core Bridge's snapshot to the dashboard's StatusView, so `mocaplink run` only
// adds what the core cannot know (the source URL, each vehicle's link URL and whether it is down).
#pragma once

#include <cstdint>
#include <optional>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include "mocaplink/core/bridge.hpp"
#include "mocaplink/core/dds_time_sync.hpp"
#include "mocaplink/core/latency_window.hpp"
#include "mocaplink/web/status.hpp"

namespace mocaplink::web {

/// The stamps a link chose for its poses itself and the sentence saying why (io::LinkClock).
struct LinkClockView {
  core::DdsPoseStamps pose_stamps = core::DdsPoseStamps::arrival;
  std::string text;
};

/// What the daemon knows beyond the core, per snapshot.
struct BridgeStatusContext {
  std::string source;              ///< source URL as configured
  std::string source_error;        ///< last source connection problem, "" if none
  std::vector<std::string> links;  ///< link URL per vehicle (index as in the Bridge)
  std::vector<bool> links_down;    ///< per vehicle: the link cannot send (may be shorter)
  std::vector<std::vector<GcsEndpointView>> gcs{};  ///< per vehicle (may be shorter)
  std::vector<LinkShareView> link_share{};          ///< per vehicle (may be shorter)
  /// Per vehicle (may be shorter): the stamps a link chose itself and why (ros2:// links,
  /// io::Link::clock()); nullopt where the core's apply.
  std::vector<std::optional<LinkClockView>> link_clocks{};
  /// The bridge's own latency over the latest frames (the daemon measures it), if any.
  std::optional<core::LatencySummary> bridge_latency{};
  /// Frames the daemon skipped because they reached its loop too late (core::LateFrames).
  std::uint64_t late_frames_skipped = 0;
  /// Frames the daemon skipped because a newer one was already waiting (core::LateFrames).
  std::uint64_t superseded_frames = 0;
  std::uint64_t source_rejected = 0;     ///< packets the source dropped unread, cumulative
  std::string source_rejected_reason{};  ///< why the latest was dropped, "" if none or unsaid
};

/// "quadrotor", "ground_rover", ... (MAV_TYPE), or the number when not in our table.
[[nodiscard]] std::string mav_type_name(std::uint8_t type);
/// "px4", "ardupilotmega", "generic", ... (MAV_AUTOPILOT), or the number.
[[nodiscard]] std::string mav_autopilot_name(std::uint8_t autopilot);
/// Flight mode from a HEARTBEAT: PX4 main/sub modes (custom_mode bytes 2 and 3), ArduPilot
/// Copter/Plane/Rover mode numbers by vehicle type; otherwise "custom_mode N".
[[nodiscard]] std::string flight_mode_name(std::uint8_t autopilot, std::uint8_t type,
                                           std::uint32_t custom_mode);

/// Fills `v`'s autopilot, origin advice, setup, statustext, estimator and delay_ms from the
/// vehicle's set-up snapshot (core::VehicleSetup), as GET /api/status does; `mocaplink vehicle
/// setup --json` prints the same fields.
void fill_setup_view(const core::VehicleStatus& in, core::HostTime now, VehicleView& v);

/// Builds StatusViews from Bridge snapshots. Every rate in them is the core's, measured over a
/// fixed window ending at the snapshot's time (frame_rate_hz: station.hpp; send_rate_hz:
/// sender.hpp), so a view does not depend on earlier calls. Not thread-safe: call it from the
/// thread that owns the Bridge (the daemon's event loop).
class BridgeStatusBuilder {
 public:
  /// `started` is the host time the daemon started (uptime_s counts from it).
  explicit BridgeStatusBuilder(core::HostTime started);

  [[nodiscard]] StatusView build(const core::BridgeSnapshot& snapshot,
                                 const BridgeStatusContext& context) const;

 private:
  core::HostTime started_;
};

}  // namespace mocaplink::web
