// `qtm://` as a Source: the native Qualisys QTM RT client (no Qualisys SDK), on its own thread.
//
// Per connection (qtm-rt.md §3): TCP connect (TCP_NODELAY) → the welcome `QTM RT Interface
// connected` → `Version 1.n` from the URL's version (default 1.28) down to 1.18 until one is set →
// `GetParameters General 6D` (body names in either XML format, §5; General frequency) →
// `StreamFrames AllFrames [UDP:port] <component>` on the TCP connection or to our UDP socket →
// data packets mapped to MocapFrames (wire/qtm_frame.hpp).
//
// Body names: re-read after the events of §2.3 (2, 4, 7, 9, 11, 12), and whenever a frame's body
// count differs from the list; until the new list arrives no frame is delivered. "Parameters not
// available" (or an error) is retried every second. Duplicate names: those bodies are always
// untracked (never an ambiguous pose) and last_error() says so.
//
// Faults: a packet with a size below 8 or above max_packet_bytes, a bad welcome, a closed socket,
// or silence (no packet for silence_timeout, then a `ByteOrder` probe unanswered for another
// silence_timeout) drops the connection and the client reconnects on the `retry` schedule
// (core/retry_schedule.hpp: at once, then every 200 ms, later doubling; reset once a version was
// set). A malformed data
// packet or XML is counted (SourceCounters::malformed) and dropped without dropping the
// connection. State `disconnected` is reported at once and no frame is delivered until the new
// connection has read fresh parameters and a fresh frame: no stale pose survives a disconnect.
#pragma once

#include <atomic>
#include <chrono>
#include <cstdint>
#include <memory>
#include <mutex>
#include <string>
#include <thread>

#include "mocaplink/core/retry_schedule.hpp"
#include "mocaplink/sources/descriptor.hpp"
#include "mocaplink/sources/loop_thread.hpp"
#include "mocaplink/sources/qtm_options.hpp"
#include "mocaplink/sources/source.hpp"

namespace mocaplink::sources {

struct QtmSourceOptions {
  QtmOptions target;
  /// When to try again after losing the server: at once (50 ms), then every 200 ms for 5 s, then
  /// doubling to 5 s (core/retry_schedule.hpp); back to the start once a connection worked.
  core::RetryPolicy retry{};
  std::chrono::milliseconds connect_timeout{5000};
  /// Silence for this long sends a probe; silence for twice this long drops the connection.
  std::chrono::milliseconds silence_timeout{2000};
  std::chrono::milliseconds parameters_retry{1000};
  std::uint32_t max_packet_bytes = wire::qtm::kDefaultMaxPacketBytes;
};

/// QTM-specific counters, beyond SourceCounters; read from any thread.
struct QtmCounters {
  std::atomic<std::uint64_t> packets{0};  ///< packets read (TCP and UDP, all types)
  std::atomic<std::uint64_t> bytes{0};
  std::atomic<std::uint64_t> connections{0};           ///< versions set
  std::atomic<std::uint64_t> events{0};                ///< event packets
  std::atomic<std::uint64_t> parameter_reads{0};       ///< body lists read
  std::atomic<std::uint64_t> frames_without_names{0};  ///< data before/while the list was re-read
  std::atomic<std::uint64_t> body_count_changes{0};    ///< data whose count differed from the list
  std::atomic<std::uint64_t> invalid_poses{0};         ///< finite but not a pose (not NaN)
  std::atomic<std::uint64_t> repeated_frames{0};       ///< same or older frame number (UDP)
  std::atomic<std::uint64_t> no_more_data{0};          ///< "No More Data" packets
  std::atomic<std::uint64_t> server_errors{0};         ///< error packets
  std::atomic<std::uint64_t> timeouts{0};              ///< connections dropped for silence
};

class QtmSource final : public Source {
 public:
  QtmSource(QtmSourceOptions options, std::string url);
  ~QtmSource() override;

  /// Spawns the client thread; callbacks run on it. Call once.
  void start(FrameSink on_frame, StateSink on_state) override;
  /// Closes the connection and joins; no callback runs after it returns. Idempotent.
  void stop() override;
  [[nodiscard]] std::string url() const override { return url_; }
  [[nodiscard]] const SourceCounters& counters() const override { return counters_; }
  [[nodiscard]] const QtmCounters& qtm_counters() const { return qtm_counters_; }
  /// The most recent connection error, dropped-packet reason or warning ("" if none); any thread.
  [[nodiscard]] std::string last_error() const { return last_error_.get(); }

 private:
  class Session;  // Asio state, lives on the client thread (qtm_source.cpp)
  friend class Session;
  void set_last_error(std::string error) { last_error_.set(std::move(error)); }

  QtmSourceOptions options_;
  std::string url_;
  SourceCounters counters_;
  QtmCounters qtm_counters_;
  LastError last_error_;
  LoopThread<Session> session_;  // last: joined before the members the session uses go
};

/// qtm:// for the source registry: parse_qtm_options, a QtmSource, and the QtmServer emulator
/// for `serve --protocol qtm`.
[[nodiscard]] SourceDescriptor qtm_source_descriptor();

}  // namespace mocaplink::sources
