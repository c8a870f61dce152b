// Where a `vrpn://[TRACKERS@]HOST[:3883][?lost_ms=500&frozen_ms=0&timeout_ms=5000]` source connects
// and which trackers it keeps (DESIGN.md "Source URLs", docs/sources.md "vrpn://").
#pragma once

#include <array>
#include <chrono>
#include <cstdint>
#include <string>
#include <string_view>
#include <vector>

#include "mocaplink/config/url.hpp"
#include "mocaplink/wire/vrpn_protocol.hpp"

namespace mocaplink::sources {

struct VrpnOptions {
  std::string host;  ///< name or IPv4/IPv6 literal
  std::uint16_t port = wire::vrpn::kDefaultPort;
  /// The trackers to deliver (VRPN sender names); empty = every tracker the server describes.
  std::vector<std::string> trackers;
  /// A body reported by no tracker message for this long is lost (one all-untracked frame).
  std::chrono::milliseconds lost{500};
  /// A pose bit-identical for this long is untracked (a server repeating a lost body); 0 = never.
  std::chrono::milliseconds frozen{0};
  /// No byte from the server for this long drops the connection and reconnects.
  std::chrono::milliseconds timeout{5000};
};

/// The `vrpn://` query keys.
inline constexpr std::array<std::string_view, 3> kVrpnOptionKeys = {"frozen_ms", "lost_ms",
                                                                    "timeout_ms"};

/// A split `vrpn://` URL (query keys already checked against kVrpnOptionKeys) → its options.
[[nodiscard]] config::ValueOrError<VrpnOptions> parse_vrpn_options(const config::UrlParts& url);

}  // namespace mocaplink::sources
