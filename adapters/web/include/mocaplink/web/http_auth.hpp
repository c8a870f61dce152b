// Access rules of the dashboard server (docs/api.md "Authentication"), as pure functions.
#pragma once

#include <string_view>

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

}  // namespace mocaplink::web
