// udpin://[addr]:port — listen for the vehicle (DESIGN.md "Link URLs"; MAVProxy's udpin:, MAVSDK's
// udpin://, mavlink-router's UDP `Mode = Server`).
//
// The socket binds the configured local address and port and waits: nothing is sent before the
// vehicle has spoken (state `connecting`, frames dropped and counted in dropped_down). Every
// datagram holding a frame from the vehicle (LinkOptions::vehicle_system_id; any accepted frame
// when unset) makes its source address the one the link answers; when that address changes (the
// vehicle rebooted onto another port, a DHCP renewal), the link follows it and says so through the
// StateHandler. Frames that fail the parser (bad CRC, bad signature) never move it.
// This is how PX4 SITL's onboard link is met (it sends to 14540 from boot), and how a vehicle
// that sends to a fixed port (ArduPilot `--serial1 udpclient:`, a Wi-Fi bridge in client mode) is.
// Sends are synchronous and non-blocking, as UdpLink's.
#pragma once

#include <cstddef>
#include <cstdint>
#include <memory>
#include <string>

#include <asio/io_context.hpp>
#include <asio/ip/udp.hpp>
#include <asio/steady_timer.hpp>

#include "mocaplink/io/link.hpp"

namespace mocaplink::io {

class UdpInLink final : public Link {
 public:
  /// `host`: an IP literal, or empty for every IPv4 interface; `port` 1..65535 (0: any free port,
  /// for tests).
  UdpInLink(asio::io_context& loop, std::string host, std::uint16_t port, LinkOptions options);
  ~UdpInLink() override;

  void start(FrameHandler on_frame, StateHandler on_state) override;
  bool send(std::span<const std::uint8_t> frame) override;
  void close(std::chrono::milliseconds linger) override;
  [[nodiscard]] bool sends_in_place() const noexcept override { return true; }
  [[nodiscard]] std::size_t backlog_bytes() const noexcept override { return 0; }
  [[nodiscard]] std::string url() const override;

  /// The bound local endpoint (tests: where a vehicle must send). Unspecified before it is bound.
  [[nodiscard]] asio::ip::udp::endpoint local_endpoint() const;
  /// The address the link answers (unspecified before the vehicle spoke).
  [[nodiscard]] asio::ip::udp::endpoint peer() const { return peer_; }

 private:
  void open();
  void schedule_retry(const std::string& why);
  void receive();
  void on_datagram(std::size_t n);

  asio::io_context& loop_;
  std::string host_;
  std::uint16_t port_;
  asio::ip::udp::socket socket_;
  asio::steady_timer retry_timer_;
  asio::ip::udp::endpoint sender_;  // of the datagram being received
  asio::ip::udp::endpoint peer_;    // where sends go; valid once has_peer_
  bool has_peer_ = false;
  static constexpr std::size_t kReceiveBufferSize = 65536;  // as UdpLink's: the largest datagram
  std::unique_ptr<std::uint8_t[]> receive_buffer_ =
      std::make_unique_for_overwrite<std::uint8_t[]>(kReceiveBufferSize);
};

}  // namespace mocaplink::io
