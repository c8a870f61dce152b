// The NatNet emulator behind `mocaplink serve --protocol natnet` (natnet.md §1, §2, §9 "Project
// emulator"): a Motive stand-in that answers on its command port (NAT_CONNECT → NAT_SERVERINFO,
// NAT_REQUEST_MODELDEF → NAT_MODELDEF, NAT_ECHOREQUEST → NAT_ECHORESPONSE, NAT_REQUEST "Bitstream"
// and "Bitstream,X.Y"; NAT_KEEPALIVE and NAT_DISCONNECT unanswered) and streams every frame it is
// given as NAT_FRAMEOFDATA in the chosen bitstream version (3.0, 3.1, 4.0, 4.1 or 4.2):
//   multicast: to group:data_port from a socket whose outgoing interface is `interface` (the
//              system's default when empty), loopback delivery on, TTL 1;
//   unicast:   as Motive does (docs/sources.md "Where unicast frames come from"): from a socket
//              bound to listen_host:data_port, to the endpoint each client's NAT_CONNECT came
//              from, until it sends NAT_DISCONNECT or no NAT_KEEPALIVE for keepalive_timeout
//              (a repeated NAT_CONNECT does not count), when it gets NAT_DISCONNECTBYTIMEOUT.
//              Each client has its own bitstream version: "Bitstream,X.Y" from a connected
//              client changes its frames alone (the next three carry the "bitstream changed"
//              bit 0x08); NAT_REQUEST from an endpoint that never connected is ignored (counted).
// Bodies get ids 1, 2, … by name in order of first appearance and keep them; a frame whose body
// list differs from the previous one is served with the "models changed" bit (and the next two
// frames too, in case one is lost), and NAT_MODELDEF describes the current list (empty before the
// first frame, so the first frame is flagged too if a client asked before it). Untracked bodies
// are served with the tracking-valid bit clear and a zero pose. The frames given are z-up (the
// simulator's and recordings' world); with `y_up` (the default, as Motive streams) they are turned
// into Motive's Y-up world: (x, y, z) → (x, z, −y). Timestamps use a 10 MHz clock:
// mid-exposure = capture_time, transmit = capture_time + source_latency.
// Malformed client datagrams are counted and dropped.
#pragma once

#include <array>
#include <atomic>
#include <chrono>
#include <cstdint>
#include <memory>
#include <optional>
#include <string>
#include <string_view>
#include <thread>
#include <utility>
#include <variant>
#include <vector>

#include "mocaplink/core/mocap_frame.hpp"
#include "mocaplink/sources/descriptor.hpp"
#include "mocaplink/wire/natnet_packet.hpp"

namespace mocaplink::sources {

struct NatnetServerOptions {
  std::string listen_host = "0.0.0.0";  ///< IPv4 literal the command socket binds
  std::uint16_t port = wire::natnet::kDefaultCommandPort;  ///< 0 = any free port (tests)
  double rate_hz = 100.0;                                  ///< provider schedule, Hz
  bool multicast = true;
  std::string group = "239.255.42.99";
  /// Multicast destination port; unicast: the port frames leave from (0 = any free port, tests).
  std::uint16_t data_port = wire::natnet::kDefaultDataPort;
  std::string interface;  ///< multicast outgoing interface (IPv4); "" = the system's default
  wire::natnet::Version version{4, 1};  ///< multicast stream / a unicast client's first version
  /// Motive ends a unicast session after about 10 s without a keep-alive.
  std::chrono::milliseconds keepalive_timeout{10000};
  bool y_up = true;
  std::size_t max_clients = 64;  ///< unicast clients; further NAT_CONNECTs are ignored (counted)
};

/// The `--set` keys of `serve --protocol natnet`.
inline constexpr std::array<std::string_view, 7> kNatnetEmulatorKeys = {
    "transport", "group", "data_port", "interface", "version", "keepalive_timeout_s", "up"};

/// NatnetServerOptions from serve's options and `--set` settings, or a one-line error.
[[nodiscard]] std::variant<NatnetServerOptions, std::string> natnet_server_options(
    const EmulatorOptions& options);

/// Server counters; read from any thread.
struct NatnetServerCounters {
  std::atomic<std::uint64_t> frames{0};  ///< frames produced (provider + publish)
  std::atomic<std::uint64_t> datagrams_sent{0};
  std::atomic<std::uint64_t> clients_connected{0};  ///< NAT_CONNECTs answered
  std::atomic<std::uint64_t> clients_now{0};        ///< unicast clients being served
  std::atomic<std::uint64_t> clients_timed_out{0};  ///< unicast clients without keep-alive
  std::atomic<std::uint64_t> clients_rejected{0};
  /// NAT_REQUEST from an endpoint that never connected (unicast), or a bitstream not served or
  /// asked for on a multicast stream.
  std::atomic<std::uint64_t> requests_refused{0};
  std::atomic<std::uint64_t> model_requests{0};
  std::atomic<std::uint64_t> malformed_requests{0};
};

class NatnetServer final : public Emulator {
 public:
  explicit NatnetServer(NatnetServerOptions options);
  ~NatnetServer() override;

  /// Binds the command socket (and the multicast sender) and starts the thread. Call once.
  [[nodiscard]] std::optional<std::string> start(FrameProvider provider) override;
  [[nodiscard]] std::uint16_t port() const override { return port_; }
  /// The data port: unicast frames leave from it, multicast frames go to it. After start().
  [[nodiscard]] std::uint16_t data_port() const { return data_port_; }
  void publish(core::MocapFrame frame) override;
  void stop() override;
  /// "N frames, N clients connected, N timed out, N requests refused, N malformed requests".
  [[nodiscard]] std::string summary() const override;
  [[nodiscard]] const NatnetServerCounters& counters() const { return counters_; }

 private:
  class Impl;  // Asio state (natnet_server.cpp)
  NatnetServerOptions options_;
  NatnetServerCounters counters_;
  std::unique_ptr<Impl> impl_;
  std::thread thread_;
  std::uint16_t port_ = 0;
  std::uint16_t data_port_ = 0;
};

}  // namespace mocaplink::sources
