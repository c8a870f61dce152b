// Ground stations on a vehicle's link (issue 38; docs/daemon.md "Ground
// stations on the vehicle's link"): each vehicle's `gcs` endpoints, opened with
// the same link forms as vehicle links (io::make_link), one socket per distinct
// endpoint however many vehicles it serves. Frames pass unchanged both ways —
// signed ones too: mocaplink signs only its own — and core::GcsRouter says
// where each goes, as mavlink-router would. Frames toward a vehicle take the
// link's forwarded path (io::Link::send_forwarded): poses first. Runs on the
// daemon's loop thread; not thread-safe.
#pragma once

#include <chrono>
#include <cstddef>
#include <cstdint>
#include <functional>
#include <memory>
#include <span>
#include <string>
#include <vector>

#include <asio/io_context.hpp>

#include "mocaplink/config/config.hpp"
#include "mocaplink/core/gcs_router.hpp"
#include "mocaplink/io/link.hpp"
#include "mocaplink/web/status.hpp"

namespace mocaplink::app {

class GroundStations {
 public:
  /// Hands a ground station's frame to the vehicle in `slot` (its link's
  /// forwarded path).
  using ToVehicle = std::function<void(std::size_t slot, std::span<const std::uint8_t> frame)>;

  GroundStations(asio::io_context& loop, ToVehicle to_vehicle);
  ~GroundStations();
  GroundStations(const GroundStations&) = delete;
  GroundStations& operator=(const GroundStations&) = delete;

  /// Opens the endpoints of `vehicle`'s `gcs` list not open yet and attaches
  /// them to `slot`.
  void add_vehicle(std::size_t slot, const config::Vehicle& vehicle);
  /// The vehicle in `slot` is gone; endpoints it alone used are closed.
  void remove_vehicle(std::size_t slot);
  /// A frame the vehicle in `slot` sent: to the endpoints the router names,
  /// unchanged.
  void from_vehicle(std::size_t slot, const mavlink::FrameView& frame);
  /// Peers that went silent are logged; closed endpoints are destroyed once
  /// their handlers ran.
  void on_tick(core::HostTime now);
  /// Every endpoint serving `slot`, for the dashboard (/api/status
  /// `vehicles[].gcs`).
  [[nodiscard]] std::vector<web::GcsEndpointView> views(std::size_t slot) const;
  /// Samples the vehicle link's own and forwarded bytes (the daemon's tick); its share as the
  /// dashboard shows it (/api/status `vehicles[].link_share`), rates over the last second.
  void sample(std::size_t slot, const io::Link& link, core::HostTime now);
  [[nodiscard]] web::LinkShareView share(std::size_t slot, const io::Link& link) const;
  /// Closes every endpoint (the daemon stops).
  void close(std::chrono::milliseconds linger);

 private:
  struct Endpoint {
    std::string url;                 // canonical (config::to_string)
    std::unique_ptr<io::Link> link;  // nullptr once closed
    core::HostTime closed_at{};
  };
  void on_gcs_frame(std::size_t endpoint, const mavlink::FrameView& frame, core::HostTime t);
  std::vector<std::string> names() const;

  asio::io_context& loop_;
  ToVehicle to_vehicle_;
  std::vector<Endpoint> endpoints_;  // by core::GcsRouter::Endpoint; a closed one keeps its index
  std::vector<std::unique_ptr<io::Link>> retired_;
  std::vector<core::HostTime> retired_at_;
  core::GcsRouter router_;
  struct Meter {  // a vehicle link's bytes at the last sample, and the rates since the one before
    core::HostTime at{};
    std::uint64_t own_bytes = 0;
    std::uint64_t forwarded_bytes = 0;
    double own_bytes_per_s = 0.0;
    double forwarded_bytes_per_s = 0.0;
  };
  std::vector<Meter> meters_;         // by vehicle slot
  std::vector<std::size_t> slots_;    // scratch: a frame's vehicles
  std::vector<std::size_t> targets_;  // scratch: a frame's endpoints
};

}  // namespace mocaplink::app
