// Server side of one QTM RT connection, pure (qtm-rt.md §3, §8): the welcome, the commands a
// client sends (Version, QTMVersion, ByteOrder, GetState, GetParameters, StreamFrames,
// GetCurrentFrame) and the data packets it asked for. The adapter owns the sockets and calls in;
// every returned packet is complete and ready to write (or to send as one UDP datagram).
//
// Commands are case-insensitive, with or without the NUL; an unknown one gets the error packet
// `Parse Error`. Versions 1.1 … 1.`max_minor` are accepted; data is served only from 1.8 on (the
// float layout). A successful StreamFrames has no reply (§3.3).
// Not thread-safe: one ServerSession per connection, used from one thread.
#pragma once

#include <cstdint>
#include <optional>
#include <span>
#include <string>
#include <vector>

#include "mocaplink/wire/qtm_frame.hpp"
#include "mocaplink/wire/qtm_protocol.hpp"

namespace mocaplink::wire::qtm {

using Packets = std::vector<std::vector<std::byte>>;

struct ServerSettings {
  int max_minor = kNewestMinor;  ///< `Version 1.n` above this: `Version NOT supported`
  /// The 6DOF components StreamFrames may ask for ("All" = these).
  std::vector<Component> components = {Component::six_d, Component::six_d_residual,
                                       Component::six_d_euler, Component::six_d_euler_residual};
  double frequency_hz = 100.0;  ///< General <Frequency>, and the base of Frequency:n
};

/// Where StreamFrames asked for UDP: `address` empty = the address the command came from.
struct UdpTarget {
  std::string address;
  std::uint16_t port = 0;
};

class ServerSession {
 public:
  explicit ServerSession(ServerSettings settings) : settings_(std::move(settings)) {}

  /// The first packet on accept: `QTM RT Interface connected` + NUL.
  [[nodiscard]] static std::vector<std::byte> welcome();

  /// One client packet (its type and payload). `names` is the current body list and `latest`
  /// the newest frame (nullptr before the first). Returns the packets to send now, in order.
  [[nodiscard]] Packets on_client_packet(std::uint32_t type, std::span<const std::byte> payload,
                                         const std::vector<std::string>& names,
                                         const ServedFrame* latest);

  /// A new frame: its data packet when this client streams and the rate divisor says so.
  [[nodiscard]] std::optional<std::vector<std::byte>> on_new_frame(const ServedFrame& frame);

  /// The data packet of `frame` with this client's components.
  [[nodiscard]] std::vector<std::byte> encode(const ServedFrame& frame,
                                              const std::vector<Component>& components) const;

  [[nodiscard]] bool streaming() const { return streaming_; }
  [[nodiscard]] const std::optional<UdpTarget>& udp() const { return udp_; }
  [[nodiscard]] int minor() const { return minor_; }
  [[nodiscard]] std::uint64_t errors_sent() const { return errors_sent_; }

 private:
  std::vector<std::byte> error(const std::string& text);
  Packets stream_frames(const std::vector<std::string>& words, const ServedFrame* latest);
  std::optional<std::vector<Component>> components_of(std::span<const std::string> words,
                                                      std::string& problem) const;

  ServerSettings settings_;
  int minor_ = 1;  // QTM's default without a Version command (§3.1)
  bool streaming_ = false;
  std::vector<Component> streamed_;
  std::uint64_t divisor_ = 1;
  std::uint64_t counter_ = 0;
  std::optional<UdpTarget> udp_;
  std::uint64_t errors_sent_ = 0;
};

}  // namespace mocaplink::wire::qtm
