// Access rules of the dashboard server (docs/api.md "Authentication"), as pure functions.
#pragma once

#include <cstdint>
#include <optional>
#include <span>
#include <string>
#include <string_view>

#include "mocaplink/config/net_address.hpp"

namespace mocaplink::web {

/// True for hosts only this machine can reach: "localhost", 127.0.0.0/8 (dotted IPv4 literal),
/// "::1" (with or without brackets). Everything else — including "" and "0.0.0.0", which bind
/// every interface — counts as reachable from the network and needs a token.
[[nodiscard]] bool is_loopback_host(std::string_view host);

/// True when `authorization` is "Bearer <token>" with exactly `token` (scheme case-insensitive).
/// Compares in time independent of where the strings differ. `token` must be non-empty.
[[nodiscard]] bool bearer_token_matches(std::string_view authorization, std::string_view token);

/// Cross-site protection for mutating requests: a browser sends `Origin` ("http://host:port") on
/// cross-origin requests; it must name the same host:port as the `Host` header. No Origin header
/// (curl, scripts) is allowed.
[[nodiscard]] bool origin_allowed(std::string_view origin, std::string_view host);

/// DNS-rebinding protection: whether `host_header`, the value of a request's one Host header,
/// names this server. A page on any site can point its own name at 127.0.0.1 after it has loaded;
/// the browser then sends that name as Host (and as Origin), so only the Host tells such a request
/// apart. Allowed: a loopback host ("localhost", 127.0.0.0/8, "[::1]") without a port or with
/// `listen_port`; a name or address of `allowed_hosts` ([http] allowed_hosts, host names lower
/// case) the same way when its port is 0, or with exactly its port otherwise. Anything else, a
/// missing ("") or malformed value included, is refused. Host names compare case-insensitively.
[[nodiscard]] bool host_allowed(std::string_view host_header, std::uint16_t listen_port,
                                std::span<const config::HostPort> allowed_hosts);

/// The answer's text for a refused Host (`host_header` nullopt: the request had none, or had it
/// more than once): names the Host as sent (bytes outside printable ASCII as '?', at most 100
/// characters, so the text is always valid JSON and a single log line) and how to allow it.
[[nodiscard]] std::string host_refusal(std::optional<std::string_view> host_header);

}  // namespace mocaplink::web
