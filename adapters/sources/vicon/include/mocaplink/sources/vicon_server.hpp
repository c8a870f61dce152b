// The Vicon DataStream emulator behind `mocaplink serve --protocol vicon`: a TCP server that
// speaks the protocol of /work/shared/protocols/vicon-datastream.md to any number of clients (our
// vicon:// source, the real Vicon SDK), in all three stream modes, from frames it is given.
//
// Frames come from a FrameProvider called at `rate_hz` on the server's thread (drift-free
// schedule; after a stall of more than 5 periods the schedule skips ahead rather than bursting),
// and/or from publish() (any thread). Every frame is served to every client according to its mode
// (wire/vicon_server_session.hpp): push = every frame, a queue of `queue_frames` packets per
// client and whole frames dropped when it is full; prefetch = the next new frame per request;
// pull = the latest frame per request. Subjects keep their ids for the server's lifetime; a body
// missing from a later frame is served occluded. A client idle for 1 s gets a KeepAlive packet.
// A client that sends a malformed packet, a body above 1 MiB, or stops reading is disconnected
// (counted).
#pragma once

#include <atomic>
#include <cstdint>
#include <functional>
#include <memory>
#include <optional>
#include <string>
#include <thread>
#include <variant>

#include "mocaplink/core/mocap_frame.hpp"
#include "mocaplink/sources/descriptor.hpp"
#include "mocaplink/sources/loop_thread.hpp"

namespace mocaplink::sources {

struct ViconServerOptions {
  std::string listen_host = "0.0.0.0";  ///< IPv4/IPv6 literal to bind
  std::uint16_t port = 801;             ///< 0 = any free port (tests); see ViconServer::port()
  /// Frame rate of the provider schedule and of StreamInfo, Hz; (0, 10000]. A published frame's
  /// own frame_rate_hz, when set, is what StreamInfo advertises for it.
  double rate_hz = 100.0;
  std::size_t queue_frames = 8;  ///< per-client push queue (spec §6.2: "drop whole frames")
  std::size_t max_clients = 64;  ///< further connections are closed at once (counted)
};

/// Server counters; read from any thread.
struct ViconServerCounters {
  std::atomic<std::uint64_t> frames{0};  ///< frames produced (provider + publish)
  std::atomic<std::uint64_t> clients_accepted{0};
  std::atomic<std::uint64_t> clients_rejected{0};  ///< over max_clients
  std::atomic<std::uint64_t> clients_now{0};
  std::atomic<std::uint64_t> packets_sent{0};
  std::atomic<std::uint64_t> frames_dropped{0};      ///< push frames a slow client missed
  std::atomic<std::uint64_t> malformed_requests{0};  ///< client packets that were not DataStream
};

class ViconServer final : public Emulator {
 public:
  /// Returns the frame to serve at tick `tick` (0, 1, 2, …), or nullopt for "no frame this
  /// tick" (a dropped frame). Called on the server's thread.
  using FrameProvider = Emulator::FrameProvider;

  explicit ViconServer(ViconServerOptions options);
  ~ViconServer() override;

  /// Binds, listens and starts the server's thread. `provider` may be empty (publish() only).
  /// Errors: bad listen address, port in use, … as a message. Call once.
  [[nodiscard]] std::optional<std::string> start(FrameProvider provider) override;
  /// The bound port (after a successful start()).
  [[nodiscard]] std::uint16_t port() const override { return port_; }
  /// Serves `frame` to the clients as the newest frame; thread-safe.
  void publish(core::MocapFrame frame) override;
  /// Closes every connection and joins the thread. Idempotent.
  void stop() override;
  /// "N frames, N clients, N frames dropped for slow clients, N malformed requests".
  [[nodiscard]] std::string summary() const override;
  [[nodiscard]] const ViconServerCounters& counters() const { return counters_; }

 private:
  class Impl;  // Asio state (vicon_server.cpp)
  ViconServerOptions options_;
  ViconServerCounters counters_;
  LoopThread<Impl> impl_;
  std::uint16_t port_ = 0;
};

}  // namespace mocaplink::sources
