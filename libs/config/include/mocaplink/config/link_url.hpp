// Vehicle link URLs (DESIGN.md "Command line"): udp://host:port, tcp://host:port,
// serial:///dev/ttyUSB0?baud=921600. Syntax only; the io adapter opens them.
#pragma once

#include <cstdint>
#include <string>
#include <string_view>

#include "mocaplink/config/net_address.hpp"
#include "mocaplink/config/value_or_error.hpp"

namespace mocaplink::config {

enum class LinkKind { udp, tcp, serial };

/// "udp", "tcp", "serial".
[[nodiscard]] const char* to_string(LinkKind kind);

/// A parsed link. For udp/tcp `address` is set (port 1..65535); for serial `device` (an absolute
/// path such as "/dev/ttyUSB0") and `baud` (a standard termios rate, default 57600) are set.
struct LinkUrl {
  LinkKind kind = LinkKind::udp;
  HostPort address;
  std::string device;
  std::uint32_t baud = 0;
  friend bool operator==(const LinkUrl&, const LinkUrl&) = default;
};

/// Default serial baud rate when `?baud=` is omitted: 57600, the factory rate of SiK telemetry
/// radios and of PX4's and ArduPilot's TELEM1 port.
inline constexpr std::uint32_t kDefaultSerialBaud = 57600;

/// Parses a link URL. Rejects the limited broadcast address 255.255.255.255 and IPv4 multicast
/// (224.0.0.0/4): pose messages carry no target system, so every listener would fuse them
/// (protocols/autopilots.md §10). Errors name the problem and the accepted forms.
[[nodiscard]] ValueOrError<LinkUrl> parse_link_url(std::string_view text);

/// The canonical URL ("udp://192.168.1.21:14540", "serial:///dev/ttyUSB0?baud=921600"). Two links
/// are the same endpoint exactly when their canonical forms are equal.
[[nodiscard]] std::string to_string(const LinkUrl& link);

}  // namespace mocaplink::config
