// udp://host:port[?bind=[addr]:port] — one UDP socket per vehicle (DESIGN.md "Link URLs";
// autopilots.md §10).
//
// The socket binds an ephemeral local port — or, with `bind`, the given local address and port,
// so that every mocaplink process is the same peer to a vehicle that answers only the first
// address that spoke to it (PX4) — and connect()s to the vehicle's address, so:
//   * replies are read on the same socket, and only the vehicle's address:port can reach it;
//   * an ICMP port-unreachable (nobody listening yet, autopilot rebooting) surfaces as
//     ECONNREFUSED on the next send or receive: counted in `refused` and otherwise ignored — the
//     frame that met the error is sent again once, the loop never stops;
//   * sends are synchronous and non-blocking: a full socket buffer drops the frame
//     (dropped_backlog) instead of queueing stale poses.
// Host names are resolved when the link starts; a failure (no route, unknown host, the bind port
// owned by another process) leaves the link `down` and is retried with back-off.
#pragma once

#include <cstddef>
#include <cstdint>
#include <memory>
#include <optional>
#include <string>

#include <asio/io_context.hpp>
#include <asio/ip/udp.hpp>

#include "mocaplink/config/net_address.hpp"
#include "mocaplink/io/link_udp_socket.hpp"

namespace mocaplink::io {

class UdpLink final : public UdpSocketLink {
 public:
  /// `host`: IPv4/IPv6 literal or DNS name; `port` 1..65535. `bind`: the local address to send
  /// from (host: an IP literal, or empty for every interface; port 0 = any free one, for tests).
  UdpLink(asio::io_context& loop, std::string host, std::uint16_t port, LinkOptions options,
          std::optional<config::HostPort> bind = std::nullopt);

  bool send(std::span<const std::uint8_t> frame) override;
  /// sendmmsg: one system call for up to kMaxBatch frames; whatever the OS refuses in the batch
  /// (an ICMP error, a full buffer) goes through send() again, so it is counted the same way. A
  /// single frame goes through send(), which costs the kernel less than a sendmmsg of one.
  std::size_t send_batch(std::span<const std::span<const std::uint8_t>> frames) override;
  static constexpr std::size_t kMaxBatch = 16;
  [[nodiscard]] std::string url() const override;

 private:
  void open() override;
  void connect(const asio::ip::udp::endpoint& remote);
  void on_datagram(std::span<const std::uint8_t> bytes,
                   const asio::ip::udp::endpoint& from) override;

  std::string host_;
  std::uint16_t port_;
  std::optional<config::HostPort> bind_;
};

}  // namespace mocaplink::io
