// tcpin://[addr]:port — a TCP server for the vehicle (DESIGN.md "Link URLs"; mavros's tcp-l://,
// mavlink-router's TCP server): for a vehicle, bridge or simulator that connects out (ArduPilot
// SITL `--serial1 tcpclient:`, a Wi-Fi bridge in TCP client mode).
//
// One vehicle connection at a time. The listener stays open for the link's life; a vehicle that
// connects again (it rebooted, its Wi-Fi dropped and came back, an old connection is half open)
// replaces the connection it had at once, and the log says so: the newest connection is the one
// a vehicle can still be reached on. Until a vehicle connects the state is `connecting` and frames
// are dropped and counted (dropped_down), as for every stream link (link_stream.hpp).
#pragma once

#include <cstdint>
#include <string>

#include <asio/io_context.hpp>
#include <asio/ip/tcp.hpp>

#include "mocaplink/io/link_tcp_socket.hpp"

namespace mocaplink::io {

class TcpInLink final : public TcpSocketLink {
 public:
  /// `host`: an IP literal, or empty for every IPv4 interface; `port` 1..65535 (0: any free port,
  /// for tests).
  TcpInLink(asio::io_context& loop, std::string host, std::uint16_t port, LinkOptions options);
  ~TcpInLink() override;

  [[nodiscard]] std::string url() const override;
  /// The listening endpoint (tests: where a vehicle must connect). Unspecified before it listens.
  [[nodiscard]] asio::ip::tcp::endpoint local_endpoint() const;

 private:
  void async_open(OpenHandler done) override;
  void release() noexcept override;
  bool listen(std::error_code& error);
  void accept();
  void adopt(OpenHandler done);

  std::string host_;
  std::uint16_t port_;
  asio::ip::tcp::acceptor acceptor_;
  asio::ip::tcp::socket incoming_;  // being accepted
  asio::ip::tcp::socket pending_;   // accepted, not yet adopted
  OpenHandler waiting_;             // async_open waiting for a connection
  bool accepting_ = false;
};

}  // namespace mocaplink::io
