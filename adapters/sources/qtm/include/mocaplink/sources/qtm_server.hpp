// The QTM RT server emulator behind `mocaplink serve --protocol qtm`: a TCP server on the
// little-endian port (default 22223) that speaks qtm-rt.md to any number of clients (up to
// max_clients; the next one gets QTM's "Connection refused. Max number of clients reached."
// error packet) — our qtm:// source, the official npm client qualisys-rt, the Qualisys C++ SDK.
//
// Each connection has its own wire::qtm::ServerSession (version, XML format, stream request).
// Frames come from publish() (any thread) and/or a FrameProvider at rate_hz; each is served to
// every streaming client over TCP or as one UDP datagram to the port (and address) its
// StreamFrames named. Connections wait in the listen backlog until the first frame: a client is
// welcomed when there is a body list to give it, as a real QTM has its list before any client. The
// body list is the frame's body names in order; when it changes (a body appears or leaves, e.g.
// sim://?churn_s) every client gets event 11 (Camera Settings Changed), after which GetParameters
// answers the new list. Untracked bodies are sent as NaN. A client that stops reading loses whole
// frames (counted), then is closed when its replies pile up too.
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
#include "mocaplink/wire/qtm_server_session.hpp"

namespace mocaplink::sources {

struct QtmServerOptions {
  std::string listen_host = "0.0.0.0";  ///< IPv4/IPv6 literal to bind
  std::uint16_t port = 22223;           ///< 0 = any free port (tests); see QtmServer::port()
  double rate_hz = 100.0;               ///< provider schedule and General <Frequency>
  wire::qtm::ServerSettings session;    ///< versions and components served
  std::size_t max_clients = 10;
  /// Per-client TCP frame queue (about a second at 200 Hz); whole frames dropped when full.
  std::size_t queue_frames = 256;
};

struct QtmServerCounters {
  std::atomic<std::uint64_t> frames{0};  ///< frames produced
  std::atomic<std::uint64_t> clients_accepted{0};
  std::atomic<std::uint64_t> clients_rejected{0};  ///< over max_clients
  std::atomic<std::uint64_t> clients_now{0};
  std::atomic<std::uint64_t> packets_sent{0};    ///< TCP packets and UDP datagrams
  std::atomic<std::uint64_t> frames_dropped{0};  ///< frames a slow TCP client missed
  std::atomic<std::uint64_t> body_list_changes{0};
  std::atomic<std::uint64_t> malformed_requests{0};  ///< bad packet sizes (connection closed)
  std::atomic<std::uint64_t> errors_sent{0};         ///< error packets (Parse Error, …)
};

class QtmServer final : public Emulator {
 public:
  explicit QtmServer(QtmServerOptions options);
  ~QtmServer() override;

  [[nodiscard]] std::optional<std::string> start(FrameProvider provider) override;
  [[nodiscard]] std::uint16_t port() const override { return port_; }
  void publish(core::MocapFrame frame) override;
  void stop() override;
  /// "N frames, N clients, N body list changes, N frames dropped for slow clients, N errors sent"
  [[nodiscard]] std::string summary() const override;
  [[nodiscard]] const QtmServerCounters& counters() const { return counters_; }

 private:
  class Impl;
  QtmServerOptions options_;
  QtmServerCounters counters_;
  LoopThread<Impl> impl_;
  std::uint16_t port_ = 0;
};

}  // namespace mocaplink::sources
