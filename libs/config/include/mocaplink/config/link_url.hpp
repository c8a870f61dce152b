// Vehicle link URLs (DESIGN.md "Command line", docs/config.md "Links"): MAVLink's usual endpoint
// forms, as MAVProxy (udpin:/udpout:), MAVSDK, mavros and mavlink-router name them:
//   udp://HOST:PORT[?bind=ADDR:PORT]    send to the vehicle (replies on the same socket); `bind`
//                                       fixes the local address, so every mocaplink process is
//                                       the same peer to a vehicle that answers only its first one
//   udpin://ADDR:PORT or udpin://:PORT  listen; answer the address the vehicle last spoke from
//   tcp://HOST:PORT                     connect to the vehicle's TCP server
//   tcpin://ADDR:PORT or tcpin://:PORT  a TCP server for one vehicle connection at a time
//   serial:///dev/ttyUSB0?baud=921600   a serial port (COMn on Windows)
//   ros2://NAMESPACE or ros2://         a PX4 through its uXRCE-DDS Agent, on the [ros2] domain
//                                       (docs/ros2.md "PX4 over uXRCE-DDS")
// Syntax only; the io adapter opens them (io::make_link).
#pragma once

#include <cstdint>
#include <optional>
#include <string>
#include <string_view>

#include "mocaplink/config/net_address.hpp"
#include "mocaplink/config/value_or_error.hpp"

namespace mocaplink::config {

enum class LinkKind { udp, udpin, tcp, tcpin, serial, ros2 };

/// "udp", "udpin", "tcp", "tcpin", "serial", "ros2".
[[nodiscard]] const char* to_string(LinkKind kind);

/// A parsed link.
///   udp, tcp      `address` is the vehicle's (port 1..65535); udp may have `bind`, the local
///                 address to send from (host empty: every interface; port 1..65535).
///   udpin, tcpin  `address` is the local address to listen on (host empty: every interface).
///   serial        `device` (an absolute path such as "/dev/ttyUSB0", or COMn on Windows) and
///                 `baud` (a standard termios rate, default 57600).
///   ros2          `ros2_namespace`: PX4's topic namespace without slashes at either end ("" for
///                 none, "px4_1"); the vehicle's topics are /NAMESPACE/fmu/in|out/....
struct LinkUrl {
  LinkKind kind = LinkKind::udp;
  HostPort address;
  std::optional<HostPort> bind;
  std::string device;
  std::uint32_t baud = 0;
  std::string ros2_namespace;
  friend bool operator==(const LinkUrl&, const LinkUrl&) = default;
};

/// True for the forms that listen (udpin, tcpin): the vehicle speaks first.
[[nodiscard]] bool listens(const LinkUrl& link);

/// The local address this link must own (udpin, tcpin, udp with `bind`), or nullopt when it takes
/// an ephemeral port or is serial.
[[nodiscard]] std::optional<HostPort> local_address(const LinkUrl& link);

/// True when both links must own the same local port of the same protocol (UDP or TCP) on
/// overlapping addresses (equal, or either one every interface): the second could not bind it.
[[nodiscard]] bool same_local_port(const LinkUrl& a, const LinkUrl& b);

/// Default serial baud rate when `?baud=` is omitted: 57600, the factory rate of SiK telemetry
/// radios and of PX4's and ArduPilot's TELEM1 port.
inline constexpr std::uint32_t kDefaultSerialBaud = 57600;

/// Parses a link URL. Rejects the limited broadcast address 255.255.255.255 and IPv4/IPv6
/// multicast as a destination or listening address: pose messages carry no target system, so
/// every listener would fuse them (protocols/autopilots.md §10). Errors name the problem and the
/// accepted forms.
[[nodiscard]] ValueOrError<LinkUrl> parse_link_url(std::string_view text);

/// The canonical URL ("udp://192.168.1.21:14540?bind=:14540", "udpin://127.0.0.1:14540",
/// "serial:///dev/ttyUSB0?baud=921600"). Two links are the same endpoint exactly when their
/// canonical forms are equal.
[[nodiscard]] std::string to_string(const LinkUrl& link);

}  // namespace mocaplink::config
