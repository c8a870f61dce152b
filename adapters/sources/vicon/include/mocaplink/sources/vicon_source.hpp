// `vicon://` as a Source: the native Vicon DataStream client (no Vicon SDK), on its own thread.
//
// Per connection: TCP connect (TCP_NODELAY) → the server's greeting (ObjectEnums) → our
// ObjectEnums (wanted ∩ offered, segment data included from the start) → the stream mode request
// (push: RequestFrame(1) once; prefetch: RequestNextFrame(1) after every frame; pull:
// RequestFrame(0) once per frame period, one request in flight) → frame packets decoded with the
// §7 caches into MocapFrames (wire/vicon_mocap_frame.hpp says how each field is derived).
//
// Faults: a malformed packet, a body above max_body_bytes, a wrong tag, a closed socket or
// `silence_timeout` without any packet drops the connection (malformed is counted when the bytes
// were at fault) and the client reconnects on the `retry` schedule (core/retry_schedule.hpp: at
// once, then every 200 ms, later doubling; reset once a greeting was received). State
// `disconnected` is reported at once and no frame is delivered until a new connection has decoded a
// fresh frame: no stale pose survives a disconnect. Pull mode repeats are not delivered twice
// (counted as repeated_frames).
#pragma once

#include <atomic>
#include <chrono>
#include <cstdint>
#include <memory>
#include <mutex>
#include <string>
#include <thread>
#include <variant>

#include "mocaplink/core/retry_schedule.hpp"
#include "mocaplink/sources/descriptor.hpp"
#include "mocaplink/sources/loop_thread.hpp"
#include "mocaplink/sources/source.hpp"
#include "mocaplink/sources/vicon_options.hpp"
#include "mocaplink/wire/vicon_packet.hpp"

namespace mocaplink::sources {

struct ViconSourceOptions {
  ViconOptions target;
  /// When to try again after losing the server: at once (50 ms), then every 200 ms for 5 s, then
  /// doubling to 5 s (core/retry_schedule.hpp); back to the start once a connection worked.
  core::RetryPolicy retry{};
  std::chrono::milliseconds connect_timeout{5000};  ///< the SDK's default (§1)
  /// No packet for this long drops the connection. Our emulator sends a KeepAlive every second
  /// when it has nothing else to send; a real server streams continuously.
  std::chrono::milliseconds silence_timeout{5000};
  std::uint32_t max_body_bytes = wire::vicon::kDefaultMaxBodyBytes;
};

/// Vicon-specific counters, beyond SourceCounters; read from any thread.
struct ViconCounters {
  std::atomic<std::uint64_t> packets{0};            ///< packets read (all kinds)
  std::atomic<std::uint64_t> bytes{0};              ///< bytes read
  std::atomic<std::uint64_t> connections{0};        ///< handshakes completed
  std::atomic<std::uint64_t> repeated_frames{0};    ///< same frame id again (pull), not delivered
  std::atomic<std::uint64_t> frames_without_id{0};  ///< dynamic packets without a usable FrameInfo
  std::atomic<std::uint64_t> invalid_poses{0};      ///< non-rotation matrices, non-finite values
  std::atomic<std::uint64_t> unknown_items{0};      ///< skipped item types
  std::atomic<std::uint64_t> keep_alives{0};
  std::atomic<std::uint64_t> timeouts{0};  ///< connections dropped for silence
};

class ViconSource final : public Source {
 public:
  ViconSource(ViconSourceOptions options, std::string url);
  ~ViconSource() override;

  /// Spawns the client thread; callbacks run on it. Call once.
  void start(FrameSink on_frame, StateSink on_state) override;
  /// Closes the connection and joins; no callback runs after it returns. Idempotent.
  void stop() override;
  [[nodiscard]] std::string url() const override { return url_; }
  [[nodiscard]] const SourceCounters& counters() const override { return counters_; }
  [[nodiscard]] const ViconCounters& vicon_counters() const { return vicon_counters_; }
  /// The most recent connection error or dropped-packet reason ("" if none); any thread.
  [[nodiscard]] std::string last_error() const { return last_error_.get(); }

 private:
  class Session;  // Asio state, lives on the client thread (vicon_source.cpp)
  friend class Session;
  void set_last_error(std::string error) { last_error_.set(std::move(error)); }

  ViconSourceOptions options_;
  std::string url_;
  SourceCounters counters_;
  ViconCounters vicon_counters_;
  LastError last_error_;
  LoopThread<Session> session_;  // last: joined before the members the session uses go
};

/// vicon:// for the source registry: parse_vicon_options, a ViconSource, and the ViconServer
/// emulator for `serve --protocol vicon`.
[[nodiscard]] SourceDescriptor vicon_source_descriptor();

}  // namespace mocaplink::sources
