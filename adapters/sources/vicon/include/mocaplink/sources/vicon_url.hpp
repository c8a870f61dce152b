// Where a `vicon://host[:801][?mode=push|prefetch|pull]` source connects (DESIGN.md "Source URLs";
// the URL itself is parsed by config::parse_source_url).
#pragma once

#include <cstdint>
#include <string>

#include "mocaplink/wire/vicon_protocol.hpp"

namespace mocaplink::sources {

struct ViconUrl {
  std::string host;  ///< name or IPv4/IPv6 literal
  std::uint16_t port = wire::vicon::kDefaultPort;
  wire::vicon::StreamMode mode = wire::vicon::StreamMode::server_push;
};

}  // namespace mocaplink::sources
