// Name resolution that never blocks the event loop (internal to adapters/io). An address literal
// is answered at once; a name is resolved by asio on its own thread (getaddrinfo can stall for
// seconds when DNS is unreachable, and a stalled loop would stop every vehicle's poses).
#pragma once

#include <cstdint>
#include <memory>
#include <string>
#include <system_error>
#include <utility>
#include <vector>

#include <asio/error.hpp>
#include <asio/io_context.hpp>
#include <asio/ip/address.hpp>

namespace mocaplink::io::detail {

/// Calls `handler(error, endpoints)` with the endpoints of host:port: synchronously for an
/// address literal, later on the loop for a name. `alive` is the caller's liveness token: when it
/// has expired by the time a name's answer comes (the caller was destroyed), the handler is not
/// called. A name that does not resolve gives an error or an empty list.
template <typename Protocol, typename Handler>
void resolve_async(asio::io_context& loop, const std::string& host, std::uint16_t port,
                   std::weak_ptr<void> alive, Handler handler) {
  using Endpoint = typename Protocol::endpoint;
  using Resolver = typename Protocol::resolver;
  std::error_code literal_error;
  const auto address = asio::ip::make_address(host, literal_error);
  if (!literal_error) {
    handler(std::error_code{}, std::vector<Endpoint>{Endpoint(address, port)});
    return;
  }
  auto resolver = std::make_shared<Resolver>(loop);
  resolver->async_resolve(
      host, std::to_string(port), Resolver::numeric_service,
      [resolver, alive = std::move(alive), handler = std::move(handler)](
          const std::error_code& error, typename Resolver::results_type results) mutable {
        if (alive.expired()) return;
        std::vector<Endpoint> endpoints;
        for (const auto& entry : results) endpoints.push_back(entry.endpoint());
        handler(error, std::move(endpoints));
      });
}

}  // namespace mocaplink::io::detail

namespace mocaplink::io::detail {

/// The local endpoint to bind for `host` (an IP literal, or empty for every interface of the
/// family `v6` selects) and `port`. libs/config admits only literals here; anything else is an
/// error (asio::error::invalid_argument), never a name lookup.
template <typename Protocol>
[[nodiscard]] typename Protocol::endpoint local_endpoint(const std::string& host,
                                                         std::uint16_t port, bool v6,
                                                         std::error_code& error) {
  error.clear();
  if (host.empty()) {
    return typename Protocol::endpoint(v6 ? Protocol::v6() : Protocol::v4(), port);
  }
  const auto address = asio::ip::make_address(host, error);
  return typename Protocol::endpoint(address, port);
}

/// An earlier datagram met an ICMP port unreachable: Linux reports ECONNREFUSED on a connected
/// socket's next call, Winsock WSAECONNRESET (on an unconnected one too, on its next receive).
/// Either is counted and survived, never fatal.
[[nodiscard]] inline bool is_refused(const std::error_code& error) {
  return error == asio::error::connection_refused || error == asio::error::connection_reset;
}

/// "host:port" as users write it: brackets around an IPv6 literal, an empty host stays empty.
[[nodiscard]] inline std::string host_port_text(const std::string& host, std::uint16_t port) {
  const bool v6 = host.find(':') != std::string::npos;
  return (v6 ? "[" + host + "]" : host) + ":" + std::to_string(port);
}

}  // namespace mocaplink::io::detail
