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
#include "mocaplink/config/value_or_error.hpp"
#include "mocaplink/core/bridge.hpp"
#include "mocaplink/core/geodesy.hpp"
#include "mocaplink/core/profile.hpp"
#include "mocaplink/core/ros.hpp"
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

/// The largest DDS domain id: its RTPS ports (7400 + 250·d + …) still fit in 16 bits.
inline constexpr std::uint32_t kMaxRosDomainId = 232;
/// ROS's advice for Linux: above this the ports may meet the ephemeral range (a warning).
inline constexpr std::uint32_t kMaxAdvisedRosDomainId = 101;

/// [ros2]: the bodies on ROS 2 topics over DDS (docs/ros2.md). Checked: the namespace and frame id
/// are legal ROS names, every listed body maps to a distinct, non-empty token that makes topic
/// names of at most core::kMaxRosTopicLength, at least one thing is published.
struct Ros2Settings {
  /// 0..232 (the RTPS port arithmetic's limit); nullopt: ROS_DOMAIN_ID, else 0 — the caller reads
  /// the environment (parse_ros_domain_id) and `check` says which it took.
  std::optional<std::uint32_t> domain_id;
  std::string ns = "mocap";         ///< [ros2] namespace; "" = topics at the root
  std::string frame_id = "world";   ///< the world frame (header.frame_id, the tf parent)
  std::vector<std::string> bodies;  ///< mocap body names; empty = every body the source streams
  bool pose = true;                 ///< /NS/BODY/pose (geometry_msgs/PoseStamped)
  bool odom = true;                 ///< /NS/BODY/odom (nav_msgs/Odometry)
  bool tf = true;                   ///< /tf (tf2_msgs/TFMessage), world → body
  core::RosAxes axes = core::RosAxes::enu_flu;
  /// Where DDS discovers and sends: "all" (every interface, multicast discovery: what a ROS 2
  /// machine does by default), "loopback" (127.0.0.1 only, unicast discovery: this machine's ROS 2
  /// nodes, with ROS_LOCALHOST_ONLY=1 or ROS_AUTOMATIC_DISCOVERY_RANGE=LOCALHOST on theirs) or one
  /// IPv4 address of this machine (that interface only).
  std::string network_interface = "all";
};

/// ROS_DOMAIN_ID as rcl reads it: unset or "" is 0; otherwise a whole number (decimal, or 0x… hex,
/// or 0… octal, as strtoul with base 0), 0..232.
[[nodiscard]] ValueOrError<std::uint32_t> parse_ros_domain_id(std::string_view text);

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
  std::optional<Ros2Settings> ros2;  ///< [ros2]; absent: no ROS 2 participant at all
};

}  // namespace mocaplink::config
