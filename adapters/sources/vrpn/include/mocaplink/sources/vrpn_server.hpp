// The VRPN tracker server emulator behind `mocaplink serve --protocol vrpn`: a TCP server on 3883
// that speaks /work/shared/protocols/vrpn.md to any number of clients (our vrpn:// source, the
// real VRPN library's clients such as vrpn_print_devices), from frames it is given.
//
// Per client: our cookie at once; the client's cookie (major version 07, log mode '0'..'3'; a log
// request is ignored); then the description burst of §4.1 (every sender: "VRPN Control" and each
// body seen so far; every type: the tracker, base and connection types), then for every frame one
// `vrpn_Tracker Pos_Quat` (sensor 0) and one `vrpn_Tracker Velocity` per tracked body, in one
// write per frame, stamped with this host's wall clock at the frame's capture (the first frame's
// capture is "now"). The velocity is the body's difference from its previous report (m/s over
// the capture-time step, vel_quat the rotation over that step, vel_quat_dt the step); zero with
// an identity vel_quat on its first report or after a gap above 0.5 s. A body appearing for the
// first time is described to every client then (a tracker created while clients are connected); a
// body missing from a frame or untracked is not reported (VRPN has no tracking flag), as a server
// whose tracker disappeared. Sender ids are kept for the server's lifetime.
//
// From a client: its sender and type descriptions are kept per connection, and its
// "vrpn_Base ping_message" from a sender named like one of our trackers is answered with a
// "vrpn_Base pong_message" from that tracker, as a VRPN server's device does
// (vrpn_BaseClass.C); everything else is read and ignored (bounded: a message above 64 KiB closes
// it). Everything is sent over TCP: no UDP description is sent, a client's UDP description is
// ignored (its reports come over TCP, which every VRPN client reads). A client without `tcp://` in
// its address asks over UDP (a "lob" to the same port number: "HOST PORT" and a NUL) to be
// called back: the emulator connects to that TCP port at the datagram's source address and
// serves the connection like an accepted one (if the UDP port can be bound; else only TCP). A
// client that does not read is closed when its queue holds more than `queue_messages` writes.
#pragma once

#include <atomic>
#include <cstdint>
#include <memory>
#include <optional>
#include <string>
#include <thread>

#include "mocaplink/core/mocap_frame.hpp"
#include "mocaplink/sources/descriptor.hpp"
#include "mocaplink/sources/loop_thread.hpp"

namespace mocaplink::sources {

struct VrpnServerOptions {
  std::string listen_host = "0.0.0.0";  ///< IPv4/IPv6 literal to bind
  std::uint16_t port = 3883;            ///< 0 = any free port (tests)
  double rate_hz = 100.0;               ///< provider schedule, (0, 10000]
  std::size_t queue_messages = 4096;    ///< per-client queued writes before it is closed
  std::size_t max_clients = 64;         ///< further connections are closed at once (counted)
};

/// Server counters; read from any thread.
struct VrpnServerCounters {
  std::atomic<std::uint64_t> frames{0};  ///< frames produced (provider + publish)
  std::atomic<std::uint64_t> clients_accepted{0};
  std::atomic<std::uint64_t> clients_rejected{0};  ///< over max_clients
  std::atomic<std::uint64_t> clients_now{0};
  std::atomic<std::uint64_t> reports{0};        ///< Pos_Quat messages queued, all clients
  std::atomic<std::uint64_t> bad_cookies{0};    ///< clients closed for a wrong cookie
  std::atomic<std::uint64_t> slow_clients{0};   ///< clients closed for not reading
  std::atomic<std::uint64_t> pongs{0};          ///< pings answered, all clients
  std::atomic<std::uint64_t> lobs_answered{0};  ///< clients called back after a UDP request
  std::atomic<std::uint64_t> bad_lobs{0};       ///< UDP datagrams that were no such request
};

class VrpnServer final : public Emulator {
 public:
  explicit VrpnServer(VrpnServerOptions options);
  ~VrpnServer() override;

  [[nodiscard]] std::optional<std::string> start(FrameProvider provider) override;
  [[nodiscard]] std::uint16_t port() const override { return port_; }
  void publish(core::MocapFrame frame) override;
  void stop() override;
  /// "N frames, N clients, N reports, N bad cookies, N slow clients, N pings answered, N UDP
  /// connection requests answered".
  [[nodiscard]] std::string summary() const override;
  [[nodiscard]] const VrpnServerCounters& counters() const { return counters_; }

 private:
  class Impl;  // Asio state (vrpn_server.cpp)
  VrpnServerOptions options_;
  VrpnServerCounters counters_;
  std::uint16_t port_ = 0;
  LoopThread<Impl> worker_;  // last: stopped first
};

}  // namespace mocaplink::sources
