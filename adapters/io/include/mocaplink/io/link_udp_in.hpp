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
#include <string>

#include <asio/io_context.hpp>
#include <asio/ip/udp.hpp>

#include "mocaplink/io/link_udp_socket.hpp"

namespace mocaplink::io {

class UdpInLink final : public UdpSocketLink {
 public:
  /// `host`: an IP literal, or empty for every IPv4 interface; `port` 1..65535 (0: any free port,
  /// for tests).
  UdpInLink(asio::io_context& loop, std::string host, std::uint16_t port, LinkOptions options);

  bool send(std::span<const std::uint8_t> frame) override;
  [[nodiscard]] std::string url() const override;
  /// The address the link answers (unspecified before the vehicle spoke).
  [[nodiscard]] asio::ip::udp::endpoint peer() const { return peer_; }

 private:
  void open() override;
  void on_datagram(std::span<const std::uint8_t> bytes,
                   const asio::ip::udp::endpoint& from) override;

  std::string host_;
  std::uint16_t port_;
  asio::ip::udp::endpoint peer_;  // where sends go; valid once has_peer_
  bool has_peer_ = false;
};

}  // namespace mocaplink::io
