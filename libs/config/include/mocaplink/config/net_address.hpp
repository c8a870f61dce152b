// "host:port" as links, sources and [http] listen write it. Syntax only: nothing is resolved here
// (libs/ do no I/O); the adapters resolve host names when they open sockets.
#pragma once

#include <cstdint>
#include <string>
#include <string_view>

#include "mocaplink/config/value_or_error.hpp"

namespace mocaplink::config {

/// A host and a port. `host` is an IPv4 literal ("192.168.1.3"), an IPv6 literal without its
/// brackets ("::1"), a DNS name ("vicon-pc.lab"), or empty where the syntax allows it (a bind
/// address meaning "every interface"). Host names are stored lower case.
struct HostPort {
  std::string host;
  std::uint16_t port = 0;
  friend bool operator==(const HostPort&, const HostPort&) = default;
};

/// What parse_host_port accepts besides "host:port".
struct HostPortRules {
  bool host_optional = false;  ///< ":51001" allowed (host left empty)
  bool port_optional = false;  ///< "host" allowed (port = default_port)
  bool port_zero_ok = false;   ///< port 0 ("any free port", for tests) allowed
  std::uint16_t default_port = 0;
};

/// Parses "host:port", "[v6]:port" (and per `rules` "host" or ":port"). Errors say what is wrong:
/// "missing port", "port must be 1..65535, got 70000", "\"a b\" is not a valid host name".
[[nodiscard]] ValueOrError<HostPort> parse_host_port(std::string_view text, HostPortRules rules);

/// Validates a bare host (IPv4, IPv6 without brackets, or DNS name). Returns the normalised host.
[[nodiscard]] ValueOrError<std::string> parse_host(std::string_view text);

/// "host:port", with brackets around IPv6 literals.
[[nodiscard]] std::string to_string(const HostPort& address);

/// True for addresses only this machine can reach: "localhost", 127.0.0.0/8 and ::1. Any other
/// name counts as reachable from the network (we cannot resolve it here).
[[nodiscard]] bool is_loopback(std::string_view host);

/// True for an IPv4 literal (four decimal octets 0..255).
[[nodiscard]] bool is_ipv4_literal(std::string_view host);

}  // namespace mocaplink::config
