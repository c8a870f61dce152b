// Where a `vicon://host[:801][?mode=push|prefetch|pull]` source connects (DESIGN.md "Source URLs",
// docs/sources.md "vicon://").
#pragma once

#include <array>
#include <cstdint>
#include <string>
#include <string_view>

#include "mocaplink/config/url.hpp"
#include "mocaplink/wire/vicon_protocol.hpp"

namespace mocaplink::sources {

struct ViconOptions {
  std::string host;  ///< name or IPv4/IPv6 literal
  std::uint16_t port = wire::vicon::kDefaultPort;
  wire::vicon::StreamMode mode = wire::vicon::StreamMode::server_push;
};

/// The `vicon://` query keys.
inline constexpr std::array<std::string_view, 1> kViconOptionKeys = {"mode"};

/// A split `vicon://` URL (query keys already checked against kViconOptionKeys) → its options.
[[nodiscard]] config::ValueOrError<ViconOptions> parse_vicon_options(const config::UrlParts& url);

}  // namespace mocaplink::sources
