// The dashboard of `mocaplink run` (adapters/web, docs/api.md): a DashboardServer whose backend
// runs every request on the daemon's event loop, so the Bridge stays single-threaded.
#pragma once

#include <functional>
#include <memory>
#include <optional>
#include <string>
#include <variant>
#include <vector>

#include <asio/io_context.hpp>

#include "mocaplink/config/load.hpp"
#include "mocaplink/core/bridge.hpp"
#include "mocaplink/core/late_frames.hpp"
#include "mocaplink/core/latency_window.hpp"
#include "mocaplink/ros2/publisher.hpp"
#include "mocaplink/sources/source.hpp"
#include "mocaplink/web/vehicle_request.hpp"
#include "run_gcs.hpp"
#include "run_links.hpp"

namespace mocaplink::web {
class DashboardServer;
}

namespace mocaplink::app {

/// What the dashboard reads and changes; all of it is touched on the loop thread only.
struct DashboardAccess {
  core::Bridge& bridge;
  const config::Config& config;              ///< [http] and the source URL
  const std::vector<VehicleLink>& vehicles;  ///< by vehicle slot, as in the Bridge
  const GroundStations& ground_stations;     ///< the vehicles' `gcs` endpoints
  const std::string& source_error;           ///< the source's last problem, "" when connected
  /// The source's counters: packets it dropped unread (rejected()) and why (any thread).
  const sources::SourceCounters& source_counters;
  const core::LatencyWindow& bridge_latency;  ///< frame received → its last datagram sent
  /// Frames skipped as too late or as superseded (core/late_frames).
  const core::LateFrames& late_frames;
  /// Adds a vehicle given as the keys of a [[vehicle]] table and starts it (paused if asked).
  std::function<std::optional<web::ApiError>(const std::vector<config::VehicleKey>& keys,
                                             bool paused)>
      add_vehicle;
  /// Stops and removes the vehicle named so.
  std::function<std::optional<web::ApiError>(const std::string& name)> remove_vehicle;
  /// Changes a running vehicle (rate_hz, messages through config::update_vehicle; paused).
  std::function<std::optional<web::ApiError>(const web::UpdateVehicle& update)> update_vehicle;
  /// Writes a vehicle's set-up fixes or reboots it (core::Bridge::apply_setup, reboot_vehicle).
  std::function<std::optional<web::ApiError>(const web::SetupVehicle& setup)> setup_vehicle;
  /// The [ros2] publisher (status() from any thread); nullptr without [ros2].
  const ros2::Publisher* ros2 = nullptr;
};

class RunDashboard {
 public:
  /// Starts serving on config.http (listen, token). Returns a one-sentence error when it cannot
  /// (non-loopback without a token, address in use, host does not resolve). Call on the loop
  /// thread before loop.run(); `loop` and `access` must outlive the returned object.
  [[nodiscard]] static std::variant<std::unique_ptr<RunDashboard>, std::string> start(
      asio::io_context& loop, DashboardAccess access);

  /// Stops the server; requests still waiting for the loop give up within a second. Idempotent;
  /// the destructor calls it.
  void stop();
  ~RunDashboard();
  RunDashboard(const RunDashboard&) = delete;
  RunDashboard& operator=(const RunDashboard&) = delete;

 private:
  class Backend;
  RunDashboard() = default;
  std::unique_ptr<Backend> backend_;
  std::unique_ptr<web::DashboardServer> server_;
};

}  // namespace mocaplink::app
