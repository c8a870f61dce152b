// One io::Link per configured vehicle (DESIGN.md "Link URLs"), plus what the daemon tracks per
// link: whether it signs, and the last signing timestamp it sent (persisted, io/signing_store.hpp).
// What the vehicle is (name, body, profile, ...) is not repeated here: the Bridge holds it by the
// same slot, and the daemon's Config holds the configuration (docs/architecture.md, "A vehicle's
// description").
#pragma once

#include <cstdint>
#include <memory>
#include <optional>
#include <string>

#include <asio/io_context.hpp>

#include "mocaplink/config/config.hpp"
#include "mocaplink/io/link.hpp"

namespace mocaplink::app {

struct VehicleLink {
  std::unique_ptr<io::Link> link;       ///< nullptr: an empty vehicle slot (vehicle removed)
  bool signing = false;                 ///< the vehicle has a signing key
  std::uint64_t last_signing_10us = 0;  ///< timestamp of the latest signed frame sent (0: none)
};

/// The ROS 2 graph a ros2:// link joins: the [ros2] table's resolved domain and its interface.
struct Ros2Graph {
  std::uint32_t domain_id = 0;
  std::string network_interface;
};

/// Builds (does not start) the vehicle's link (io::make_link; ros2:// → ros2::make_px4_link on
/// `ros2`, which the config guarantees for such a link). With a signing key, incoming frames
/// are verified and unsigned ones rejected. (A serial link too slow for the profile is a
/// configuration warning: core::serial_bandwidth_warning, given by the config for `check`, `run`
/// and the dashboard.)
[[nodiscard]] VehicleLink make_vehicle_link(asio::io_context& loop, const config::Vehicle& vehicle,
                                            const std::optional<Ros2Graph>& ros2 = std::nullopt);

}  // namespace mocaplink::app
