// Where a `natnet://server[:1510][?local=IP&multicast=GROUP&data_port=N&transport=…]` source
// connects (DESIGN.md "Source URLs", docs/sources.md "natnet://").
#pragma once

#include <array>
#include <cstdint>
#include <optional>
#include <string>
#include <string_view>

#include "mocaplink/config/url.hpp"
#include "mocaplink/wire/natnet_packet.hpp"

namespace mocaplink::sources {

/// How frames reach the client: as the server says (server info, 3.0+), or forced.
enum class NatnetTransport { automatic, multicast, unicast };

struct NatnetOptions {
  std::string host;  ///< Motive's address (name or IPv4)
  std::uint16_t command_port = wire::natnet::kDefaultCommandPort;
  /// IPv4 address of the local interface to bind and join the group on; "" = any / the default.
  std::string local;
  /// Multicast group; unset = the one the server announces (239.255.42.99 before 3.0).
  std::optional<std::string> multicast_group;
  /// Data port; unset = the one the server announces (1511 before 3.0).
  std::optional<std::uint16_t> data_port;
  NatnetTransport transport = NatnetTransport::automatic;
};

/// The `natnet://` query keys.
inline constexpr std::array<std::string_view, 4> kNatnetOptionKeys = {"local", "multicast",
                                                                      "data_port", "transport"};

/// A split `natnet://` URL (query keys already checked against kNatnetOptionKeys) → its options.
[[nodiscard]] config::ValueOrError<NatnetOptions> parse_natnet_options(const config::UrlParts& url);

}  // namespace mocaplink::sources
