#include "mocaplink/web/http_auth.hpp"

#include <algorithm>
#include <cctype>
#include <cstddef>
#include <string>

namespace mocaplink::web {
namespace {

bool iequals(std::string_view a, std::string_view b) {
  if (a.size() != b.size()) return false;
  for (std::size_t i = 0; i < a.size(); ++i) {
    if (std::tolower(static_cast<unsigned char>(a[i])) !=
        std::tolower(static_cast<unsigned char>(b[i]))) {
      return false;
    }
  }
  return true;
}

// Dotted-quad IPv4 literal with first octet 127 (127.0.0.0/8 is loopback, RFC 1122 §3.2.1.3).
bool is_ipv4_loopback(std::string_view host) {
  int octets = 0;
  std::size_t i = 0;
  int first = -1;
  while (i <= host.size()) {
    std::size_t digits = 0;
    int value = 0;
    while (i < host.size() && host[i] >= '0' && host[i] <= '9' && digits < 3) {
      value = value * 10 + (host[i] - '0');
      ++i;
      ++digits;
    }
    if (digits == 0 || value > 255) return false;
    if (octets == 0) first = value;
    ++octets;
    if (i == host.size()) break;
    if (host[i] != '.' || octets == 4) return false;
    ++i;
  }
  return octets == 4 && first == 127;
}

}  // namespace

bool is_loopback_host(std::string_view host) {
  if (host.size() >= 2 && host.front() == '[' && host.back() == ']') {
    host = host.substr(1, host.size() - 2);
  }
  return iequals(host, "localhost") || host == "::1" || is_ipv4_loopback(host);
}

bool bearer_token_matches(std::string_view authorization, std::string_view token) {
  constexpr std::string_view kScheme = "Bearer ";
  if (token.empty() || authorization.size() < kScheme.size() ||
      !iequals(authorization.substr(0, kScheme.size()), kScheme)) {
    return false;
  }
  const std::string_view given = authorization.substr(kScheme.size());
  // Constant time in the content: every byte of the expected token is compared.
  unsigned diff = given.size() == token.size() ? 0U : 1U;
  for (std::size_t i = 0; i < token.size(); ++i) {
    const char g = i < given.size() ? given[i] : '\0';
    diff |=
        static_cast<unsigned>(static_cast<unsigned char>(g) ^ static_cast<unsigned char>(token[i]));
  }
  return diff == 0;
}

bool origin_allowed(std::string_view origin, std::string_view host) {
  if (origin.empty()) return true;
  for (std::string_view scheme : {std::string_view("http://"), std::string_view("https://")}) {
    if (origin.substr(0, scheme.size()) == scheme) {
      return iequals(origin.substr(scheme.size()), host);
    }
  }
  return false;  // "null" (sandboxed or file:// pages) and anything unexpected
}

bool host_allowed(std::string_view host_header, std::uint16_t listen_port,
                  std::span<const config::HostPort> allowed_hosts) {
  // The Host header is uri-host [":" port] (RFC 9110 §7.2), as a configured address is written:
  // one parser for both. Port 0 stands for "no port given" (an explicit ":0" is malformed).
  const auto requested =
      config::parse_host_port(host_header, config::HostPortRules{.port_optional = true});
  if (!requested.ok()) return false;
  const config::HostPort& host = requested.value();
  const bool default_port = host.port == 0 || host.port == listen_port;
  if (config::is_loopback(host.host)) return default_port;
  return std::any_of(allowed_hosts.begin(), allowed_hosts.end(), [&](const config::HostPort& a) {
    return iequals(a.host, host.host) && (a.port == 0 ? default_port : a.port == host.port);
  });
}

std::string host_refusal(std::optional<std::string_view> host_header) {
  if (!host_header) {
    return "refused: the request must carry exactly one Host header naming this dashboard";
  }
  constexpr std::size_t kMaxShown = 100;
  std::string shown;
  for (const char c : host_header->substr(0, kMaxShown)) {
    shown += (c >= 0x20 && c < 0x7f) ? c : '?';
  }
  if (host_header->size() > kMaxShown) shown += "...";
  return "refused: Host \"" + shown +
         "\" is not a name of this dashboard: it answers only to localhost, 127.0.0.0/8, [::1] "
         "and the names of [http] allowed_hosts, so that no web page can reach it by DNS "
         "rebinding. To open it by this name, add the name to [http] allowed_hosts or run with "
         "--http-allow-host NAME";
}

}  // namespace mocaplink::web
