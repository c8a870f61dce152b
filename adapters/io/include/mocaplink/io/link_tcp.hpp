// tcp://host:port — the bridge connects to a vehicle-side TCP server (a companion computer's
// mavlink-router TCP endpoint, PX4 SITL / ArduPilot SITL serial-over-TCP, a WiFi bridge) and
// reconnects with back-off after any failure or close (link_stream.hpp). TCP_NODELAY is set: a
// pose frame must leave now, not when Nagle's algorithm has collected a segment.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include <asio/ip/tcp.hpp>

#include "mocaplink/io/link_stream.hpp"

namespace mocaplink::io {

class TcpLink final : public StreamLink {
 public:
  /// `host`: IPv4/IPv6 literal or DNS name (resolved at each connection attempt); port 1..65535.
  TcpLink(asio::io_context& loop, std::string host, std::uint16_t port, LinkOptions options);
  ~TcpLink() override;

  [[nodiscard]] std::string url() const override;

 private:
  void async_open(OpenHandler done) override;
  void connect(const std::vector<asio::ip::tcp::endpoint>& endpoints, OpenHandler done);
  void async_write_all(std::span<const std::uint8_t> bytes, IoHandler done) override;
  void async_read_some(std::span<std::uint8_t> buffer, IoHandler done) override;
  void close_transport() noexcept override;
  [[nodiscard]] std::optional<std::size_t> unsent_bytes() const noexcept override;

  std::string host_;
  std::uint16_t port_;
  asio::ip::tcp::socket socket_;
};

}  // namespace mocaplink::io
