// `vicon://host[:801][?mode=push|prefetch|pull]` (DESIGN.md "Source URLs").
#pragma once

#include <cstdint>
#include <string>
#include <string_view>
#include <variant>

#include "mocaplink/wire/vicon_protocol.hpp"

namespace mocaplink::sources {

struct ViconUrl {
  std::string host;  ///< name or IPv4/IPv6 literal ([::1] form for IPv6 with a port)
  std::uint16_t port = wire::vicon::kDefaultPort;
  wire::vicon::StreamMode mode = wire::vicon::StreamMode::server_push;
};

/// Parses a vicon:// URL. Errors (the string alternative) say what is wrong: wrong scheme, empty
/// host, bad port (1..65535), unknown query key or mode value. Pure; thread-safe.
[[nodiscard]] std::variant<ViconUrl, std::string> parse_vicon_url(std::string_view url);

}  // namespace mocaplink::sources
