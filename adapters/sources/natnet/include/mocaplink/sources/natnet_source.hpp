// `natnet://` as a Source: the native OptiTrack NatNet client (no NatNet SDK), on its own thread.
//
// Per connection (natnet.md §1): a command socket bound to `local`:0 sends NAT_CONNECT to
// server:1510 (again every connect_retry) until NAT_SERVERINFO answers; its bitstream version must
// be 2.5 ≤ v < 5.0. Transport, group and data port come from the server info (3.0+) unless the URL
// forces them. A data socket is bound to `local`:data_port (SO_REUSEADDR) and, for multicast,
// joins the group on the `local` interface (the default interface when `local` is unset). Unicast
// sends NAT_KEEPALIVE every keep_alive from the command socket and reads frames on both sockets:
// on the command socket, those from the server's data port (where Motive sends them from) and its
// command port; a datagram from any other endpoint there is foreign (counted, dropped). Then
// NAT_REQUEST_MODELDEF; frames are delivered once the model definitions are known, bodies named by
// them (wire/natnet_mocap_frame.hpp). The model definitions are re-requested when a frame says the
// model list changed or names an unknown id (at most every model_retry). A frame that says the
// bitstream changed (§4.7 0x08, or 0x04: Edit mode or, in the samples, the same) or that does not
// decode makes the client ask for the server info (and a NatNet 4 server's "Bitstream") again at
// once, at most every 250 ms; a new version drops the model table and asks for it again.
// NAT_DISCONNECTBYTIMEOUT from the server ends the session (reconnect after the back-off).
//
// Faults: a malformed datagram is counted and dropped. No frame for silence_timeout (or no server
// info within it) drops the connection: state `disconnected` at once, a retry on the `retry`
// schedule (core/retry_schedule.hpp: at once, then every 200 ms, later doubling), then a new
// connection that must receive a fresh server
// info and model definitions before any frame is delivered again: no stale pose survives. Frames
// repeated on the second socket are delivered once (duplicate_frames).
#pragma once

#include <atomic>
#include <chrono>
#include <cstdint>
#include <string>

#include "mocaplink/core/retry_schedule.hpp"
#include "mocaplink/sources/descriptor.hpp"
#include "mocaplink/sources/loop_thread.hpp"
#include "mocaplink/sources/natnet_options.hpp"
#include "mocaplink/sources/source.hpp"

namespace mocaplink::sources {

struct NatnetSourceOptions {
  NatnetOptions target;
  std::chrono::milliseconds connect_retry{1000};  ///< NAT_CONNECT resent until server info
  std::chrono::milliseconds keep_alive{1000};     ///< unicast NAT_KEEPALIVE period (§1.2)
  std::chrono::milliseconds silence_timeout{3000};
  /// When to try again after losing the server: at once (50 ms), then every 200 ms for 5 s, then
  /// doubling to 5 s (core/retry_schedule.hpp); back to the start once a connection worked.
  core::RetryPolicy retry{};
  std::chrono::milliseconds model_retry{500};  ///< least time between model requests
};

/// NatNet-specific counters, beyond SourceCounters; read from any thread.
struct NatnetCounters {
  std::atomic<std::uint64_t> packets{0};           ///< datagrams read (both sockets)
  std::atomic<std::uint64_t> connections{0};       ///< server infos that started a session
  std::atomic<std::uint64_t> model_requests{0};    ///< NAT_REQUEST_MODELDEF sent
  std::atomic<std::uint64_t> model_reloads{0};     ///< NAT_MODELDEF applied
  std::atomic<std::uint64_t> unknown_ids{0};       ///< bodies dropped: id not in the table
  std::atomic<std::uint64_t> invalid_poses{0};     ///< valid bit but non-finite / non-unit pose
  std::atomic<std::uint64_t> duplicate_frames{0};  ///< same or older frame number, not delivered
  std::atomic<std::uint64_t> frames_before_models{0};  ///< frames dropped: no model defs yet
  std::atomic<std::uint64_t> trailing_bytes{0};        ///< datagrams longer than their header says
  std::atomic<std::uint64_t> keep_alives{0};
  /// On the command socket from neither the server's command port nor its data port.
  std::atomic<std::uint64_t> foreign_datagrams{0};
  /// Frames from the server's command port: read, though Motive sends unicast frames from its
  /// data port and OptiTrack's NatNet library drops these (docs/sources.md).
  std::atomic<std::uint64_t> frames_from_command_port{0};
  std::atomic<std::uint64_t> disconnects_by_server{0};  ///< NAT_DISCONNECTBYTIMEOUT received
  std::atomic<std::uint64_t> revalidations{0};      ///< server info asked again (flag, bad frame)
  std::atomic<std::uint64_t> bitstream_changes{0};  ///< version changed within a session
  std::atomic<std::uint64_t> timeouts{0};           ///< connections dropped for silence
};

class NatnetSource final : public Source {
 public:
  NatnetSource(NatnetSourceOptions options, std::string url);
  ~NatnetSource() override;

  /// Spawns the client thread; callbacks run on it. Call once.
  void start(FrameSink on_frame, StateSink on_state) override;
  /// Sends NAT_DISCONNECT (unicast), closes the sockets and joins. Idempotent.
  void stop() override;
  [[nodiscard]] std::string url() const override { return url_; }
  [[nodiscard]] const SourceCounters& counters() const override { return counters_; }
  [[nodiscard]] const NatnetCounters& natnet_counters() const { return natnet_counters_; }
  /// The most recent connection error or dropped-datagram reason ("" if none); any thread.
  [[nodiscard]] std::string last_error() const { return last_error_.get(); }

 private:
  class Session;  // Asio state, lives on the client thread (natnet_source.cpp)
  friend class Session;

  NatnetSourceOptions options_;
  std::string url_;
  SourceCounters counters_;
  NatnetCounters natnet_counters_;
  LastError last_error_;
  LoopThread<Session> thread_;  // last: stopped before the state its session uses
};

/// natnet:// for the source registry: parse_natnet_options, a NatnetSource, the Y-up reminder and
/// the NatnetServer emulator for `serve --protocol natnet`.
[[nodiscard]] SourceDescriptor natnet_source_descriptor();

}  // namespace mocaplink::sources
