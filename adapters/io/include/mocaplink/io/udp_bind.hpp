// A bound UDP socket from a `udp://host:port` URL, for tools that listen (`mocaplink mavlink
// listen`). Vehicle links (which send to udp://host:port and read replies on the same socket) are
// a different thing and live with the link code.
#pragma once

#include <cstdint>
#include <optional>
#include <string>
#include <string_view>

#include <asio/io_context.hpp>
#include <asio/ip/udp.hpp>

namespace mocaplink::io {

/// Host and port of a `udp://host:port` URL. host is a numeric address or a name; empty for
/// "udp://:port" (all interfaces). IPv6 literals are written in brackets: udp://[::1]:14550.
struct UdpUrl {
  std::string host;
  std::uint16_t port = 0;
};

/// Parses `udp://host:port` (port 0–65535; 0 lets the system choose). On failure returns nullopt
/// and sets `error` to a one-line reason.
[[nodiscard]] std::optional<UdpUrl> parse_udp_url(std::string_view url, std::string& error);

/// Opens a UDP socket bound to `url` (host resolved; empty host = 0.0.0.0) on `loop`. On failure
/// returns nullopt and sets `error` (resolution or bind failure, with the system's message).
/// The socket is plain Asio: use it from the loop's thread only.
[[nodiscard]] std::optional<asio::ip::udp::socket> bind_udp(asio::io_context& loop,
                                                            const UdpUrl& url, std::string& error);

}  // namespace mocaplink::io
