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
#include <asio/steady_timer.hpp>

#include "mocaplink/config/net_address.hpp"
#include "mocaplink/io/link.hpp"

namespace mocaplink::io {

class UdpLink final : public Link {
 public:
  /// `host`: IPv4/IPv6 literal or DNS name; `port` 1..65535. `bind`: the local address to send
  /// from (host: an IP literal, or empty for every interface; port 0 = any free one, for tests).
  UdpLink(asio::io_context& loop, std::string host, std::uint16_t port, LinkOptions options,
          std::optional<config::HostPort> bind = std::nullopt);
  ~UdpLink() override;

  void start(FrameHandler on_frame, StateHandler on_state) override;
  bool send(std::span<const std::uint8_t> frame) override;
  /// sendmmsg: one system call for up to kMaxBatch frames; whatever the OS refuses in the batch
  /// (an ICMP error, a full buffer) goes through send() again, so it is counted the same way. A
  /// single frame goes through send(), which costs the kernel less than a sendmmsg of one.
  std::size_t send_batch(std::span<const std::span<const std::uint8_t>> frames) override;
  static constexpr std::size_t kMaxBatch = 16;
  void close(std::chrono::milliseconds linger) override;
  [[nodiscard]] bool sends_in_place() const noexcept override { return true; }
  [[nodiscard]] std::size_t backlog_bytes() const noexcept override { return 0; }
  [[nodiscard]] std::string url() const override;

  /// The local endpoint (tests: where the vehicle's replies must go). Unspecified before `up`.
  [[nodiscard]] asio::ip::udp::endpoint local_endpoint() const;

 private:
  void open();
  void connect(const asio::ip::udp::endpoint& remote);
  void schedule_retry(const std::string& why);
  void receive();

  asio::io_context& loop_;
  std::string host_;
  std::uint16_t port_;
  std::optional<config::HostPort> bind_;
  asio::ip::udp::socket socket_;
  asio::steady_timer retry_timer_;
  // Largest UDP payload: a datagram never holds more, and a smaller buffer would truncate a
  // datagram packed with several frames. On the heap and not zeroed: the OS makes a page of it
  // resident only once a datagram reaches it (fresh heap memory), so a vehicle that sends one
  // frame per datagram costs about a page rather than 64 KiB (peak RSS at 1000 vehicles,
  // docs/performance.md), and the link object stays small.
  static constexpr std::size_t kReceiveBufferSize = 65536;
  std::unique_ptr<std::uint8_t[]> receive_buffer_ =
      std::make_unique_for_overwrite<std::uint8_t[]>(kReceiveBufferSize);
};

}  // namespace mocaplink::io
