// The dashboard's HTTP server (docs/api.md): the embedded page at "/", the REST API under /api/
// and server-sent events at /api/events, over cpp-httplib with one thread per connection (an idle
// or slow client never holds a thread another request needs), a cap on connections per client
// address and a deadline on every request (connection_limits.hpp).
#pragma once

#include <chrono>
#include <cstddef>
#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include "mocaplink/config/net_address.hpp"
#include "mocaplink/web/dashboard_backend.hpp"
#include "mocaplink/web/vehicle_request.hpp"

namespace mocaplink::web {

struct DashboardServerConfig {
  std::string host = "127.0.0.1";  ///< address to bind: IPv4/IPv6 literal or name; "0.0.0.0" = all
  std::uint16_t port = 8080;       ///< 0 = any free port (tests; see DashboardServer::port())
  /// "" = no authentication, allowed only on loopback hosts. Otherwise every /api/ request needs
  /// "Authorization: Bearer <token>".
  std::string token{};
  /// Names (lower case) besides localhost, 127.0.0.0/8 and [::1] that a request's Host may give
  /// (port 0: without a port or with the listening one; otherwise exactly that port). Without a
  /// token every request, page files included, must name one of these or a loopback host, or it
  /// is answered 403 (DNS rebinding, http_auth.hpp host_allowed). With a token the Host is checked
  /// only when this list is not empty: the token is the protection, and a server on 0.0.0.0 is
  /// reached by addresses it cannot know.
  std::vector<config::HostPort> allowed_hosts{};
  std::chrono::milliseconds event_period{100};  ///< /api/events period (about 10 updates/s), > 0
  std::size_t max_event_clients = 8;            ///< concurrent /api/events streams; more get 503
  /// Connections served at once, one thread each (idle ones cost no CPU); more wait for one.
  std::size_t max_connections = 256;
  /// Connections one client address may hold at once, ≥ 1; more are closed at once and counted
  /// (`http.connections_refused` in /api/status). A stuck tab or a scanner cannot take them all.
  std::size_t max_connections_per_client = 32;
  /// A request (request line, headers and body) must arrive within this from its first byte, and
  /// without a silence of `idle_timeout` between bytes; otherwise it is answered 408 and the
  /// connection closed (`http.requests_timed_out`). > 0. Answers and event streams are not bound.
  std::chrono::milliseconds request_timeout{5000};
  /// A connection silent this long before or between requests is closed, > 0.
  std::chrono::milliseconds idle_timeout{2000};
};

/// Owns the listening socket and the worker threads. start() once; stop() (or the destructor)
/// ends every request and stream. Thread-safety: start/stop/port from one owning thread; the
/// backend is called from worker threads (see DashboardBackend).
class DashboardServer {
 public:
  /// `backend` must outlive the server.
  DashboardServer(DashboardBackend& backend, DashboardServerConfig config);
  ~DashboardServer();
  DashboardServer(const DashboardServer&) = delete;
  DashboardServer& operator=(const DashboardServer&) = delete;

  /// Checks the configuration, binds and starts serving on a background thread. When it returns
  /// success, the socket is listening (clients may connect at once). Errors, one sentence each:
  /// a non-loopback host without a token ("refusing to listen on 0.0.0.0:8080 without [http]
  /// token ..."), a host that does not resolve or a port in use ("cannot listen on
  /// 127.0.0.1:8080: Address already in use"). Starting twice is an error.
  [[nodiscard]] std::optional<std::string> start();

  /// The bound port (the real one when configured with 0); 0 before a successful start().
  [[nodiscard]] std::uint16_t port() const;

  /// Stops accepting, ends event streams and joins the threads. Idempotent.
  void stop();

 private:
  class Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace mocaplink::web
