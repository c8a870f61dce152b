// Where a `qtm://HOST[:22223][?udp=PORT&component=6d&version=1.28]` source connects and how it
// streams (docs/sources.md "qtm://"), and the `serve --protocol qtm --set` settings.
#pragma once

#include <array>
#include <cstdint>
#include <optional>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include "mocaplink/config/url.hpp"
#include "mocaplink/wire/qtm_protocol.hpp"
#include "mocaplink/wire/qtm_server_session.hpp"

namespace mocaplink::sources {

struct QtmOptions {
  std::string host;  ///< name or IPv4/IPv6 literal
  std::uint16_t port = wire::qtm::kDefaultPort;
  /// Stream over UDP to this local port (0 = any free port) instead of the TCP connection.
  std::optional<std::uint16_t> udp_port;
  wire::qtm::Component component = wire::qtm::Component::six_d;
  int newest_minor = wire::qtm::kNewestMinor;  ///< first `Version 1.n` tried (down to 1.18)
};

/// The `qtm://` query keys.
inline constexpr std::array<std::string_view, 3> kQtmOptionKeys = {"udp", "component", "version"};

/// A split `qtm://` URL (query keys already checked against kQtmOptionKeys) → its options.
[[nodiscard]] config::ValueOrError<QtmOptions> parse_qtm_options(const config::UrlParts& url);

/// The `serve --protocol qtm --set KEY=VALUE` keys.
inline constexpr std::array<std::string_view, 3> kQtmEmulatorKeys = {"version", "components",
                                                                     "max_clients"};

/// `--set` settings → the emulator's session settings and client limit, or one line naming the
/// bad setting.
struct QtmEmulatorSettings {
  wire::qtm::ServerSettings session;
  std::size_t max_clients = 10;  ///< QTM's limit (qtm-rt.md §1)
};
[[nodiscard]] config::ValueOrError<QtmEmulatorSettings> parse_qtm_emulator_settings(
    const std::vector<std::pair<std::string, std::string>>& settings);

}  // namespace mocaplink::sources
