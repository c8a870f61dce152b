// The typed, validated configuration of mocaplink (DESIGN.md "Configuration", docs/config.md).
// A Config is only ever produced by parse_config / load_config / apply_overrides / demo_config,
// which guarantee every documented range and cross-field rule; consumers need not re-check.
// Thread-safety: plain value types.
#pragma once

#include <array>
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "mocaplink/config/axis.hpp"
#include "mocaplink/config/link_url.hpp"
#include "mocaplink/config/net_address.hpp"
#include "mocaplink/config/profile.hpp"
#include "mocaplink/config/source_url.hpp"
#include "mocaplink/core/bridge.hpp"
#include "mocaplink/core/geodesy.hpp"
#include "mocaplink/core/profile.hpp"
#include "mocaplink/core/sender.hpp"
#include "mocaplink/core/tracker.hpp"

namespace mocaplink::config {

/// [mocap]: where poses come from and how the mocap world frame maps to NED.
struct MocapSettings {
  SourceUrl source;                         ///< required
  core::SignedAxis up = core::axis::pos_z;  ///< mocap axis pointing up (Vicon/QTM +z; Motive +y)
  core::North north = core::axis::pos_x;    ///< mocap axis or angle that becomes north; ⟂ up
  core::SignedAxis body_forward = core::axis::pos_x;  ///< default rigid-body axis out of the nose
  core::SignedAxis body_up = core::axis::pos_z;  ///< default body axis up when level; ⟂ forward
};

/// One [[vehicle]]: a mocap body whose poses go to one autopilot over one link. `spec` is the
/// core's vehicle description, checked by the config rules:
///   name           unique; 1..64 of [A-Za-z0-9_.-] (used in file names and URLs)
///   body           rigid-body name in the mocap system (1..256 bytes, no control chars)
///   system_id      1..255, unique per link; also the source sysid we send with
///   component_id   2..255 (1 is the autopilot itself); default kDefaultComponentId
///   messages       non-empty, no duplicates, iff profile == custom
///   rate_hz        0 < rate ≤ core::kMaxSenderRateHz; pose messages per second
///   body_axes      from the vehicle's body_forward / body_up, or [mocap]'s (forward() / up())
///   enabled        false: configured but nothing is sent
struct Vehicle {
  core::VehicleSpec spec;
  LinkUrl link;
  /// Ground-station endpoints sharing the vehicle's link (docs/config.md "Ground stations"):
  /// frames pass both ways unchanged, poses first. No duplicates; none equal to a vehicle link.
  std::vector<LinkUrl> gcs;
};

/// [http]: the dashboard / REST API.
struct HttpSettings {
  HostPort listen{"127.0.0.1", 8080};  ///< port 0 = any free port (tests)
  std::string token;  ///< "" or ≥ 16 characters; required when listen is not loopback
  /// Names besides localhost, 127.0.0.0/8 and [::1] by which the dashboard may be opened (the
  /// request's Host): "lab-pc" (lower case) with port 0 = without a port or with listen's, or
  /// "lab-pc:9000" = exactly that port. Without a token every other Host is refused (DNS
  /// rebinding); with a token the Host is checked only when this is not empty (docs/api.md).
  std::vector<HostPort> allowed_hosts;
  /// Dashboard connections one client address may hold at once, 1..256 (the server's total).
  std::uint32_t max_connections_per_client = 32;
};

struct Config {
  MocapSettings mocap;
  /// [origin]: the geodetic position of the mocap frame's origin (WGS84; altitude above mean sea
  /// level, as HIL_GPS / GPS_INPUT / SET_GPS_GLOBAL_ORIGIN carry it; −90 ≤ lat ≤ 90,
  /// −180 ≤ lon ≤ 180, −1000 ≤ alt ≤ 10000 m). Required by px4-gps, ardupilot-gps, classic,
  /// hil_gps, gps_input.
  std::optional<core::GeodeticPosition> origin;
  std::vector<Vehicle> vehicles;
  /// [tracking]: the tracker settings — the core's defaults with the keys the file sets (sanity
  /// bounds checked per key here, the tracker's cross-key rules by core::validate).
  core::TrackerConfig tracking;
  HttpSettings http;
};

}  // namespace mocaplink::config
