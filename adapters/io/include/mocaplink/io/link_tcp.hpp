// tcp://host:port — the bridge connects to a vehicle-side TCP server (a companion computer's
// mavlink-router TCP endpoint, PX4 SITL / ArduPilot SITL serial-over-TCP, a WiFi bridge) and
// reconnects with back-off after any failure or close (link_stream.hpp). The socket and its stream
// hooks (TCP_NODELAY among them) are link_tcp_socket.hpp's.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include <asio/ip/tcp.hpp>

#include "mocaplink/io/link_tcp_socket.hpp"

namespace mocaplink::io {

class TcpLink final : public TcpSocketLink {
 public:
  /// `host`: IPv4/IPv6 literal or DNS name (resolved at each connection attempt); port 1..65535.
  TcpLink(asio::io_context& loop, std::string host, std::uint16_t port, LinkOptions options);
  ~TcpLink() override;

  [[nodiscard]] std::string url() const override;

 private:
  void async_open(OpenHandler done) override;
  void connect(const std::vector<asio::ip::tcp::endpoint>& endpoints, OpenHandler done);

  std::string host_;
  std::uint16_t port_;
};

}  // namespace mocaplink::io
