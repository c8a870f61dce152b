// `vrpn://` as a Source: a receive-only VRPN tracker client over TCP (no VRPN library), on its own
// thread (/work/shared/protocols/vrpn.md §8).
//
// Per connection: TCP connect (TCP_NODELAY) → our cookie (log mode '0') → the server's cookie
// (major version 07 required) → messages: sender/type descriptions fill the connection's id tables,
// `vrpn_Tracker Pos_Quat` reports of the wanted trackers go through the FrameAssembler
// (wire/vrpn_client.hpp: host-time frames, frame_step 0, loss after `lost` of silence, frozen
// poses untracked), everything else is ignored. We never describe anything and never ask for UDP:
// the server sends every report over TCP.
//
// Faults: a malformed message (bad length, bad description, bad Pos_Quat), a wrong cookie, a closed
// socket or `timeout` without a byte drops the connection (malformed counted when the bytes were at
// fault) and the client reconnects on the `retry` schedule (core/retry_schedule.hpp: at once,
// then every 200 ms, later doubling; reset once a server cookie was accepted). State `disconnected`
// is reported at once; the round being assembled is discarded and the id tables are dropped, so no
// pose of the old connection reaches a frame after it.
#pragma once

#include <atomic>
#include <chrono>
#include <cstdint>
#include <memory>
#include <mutex>
#include <string>
#include <thread>
#include <vector>

#include "mocaplink/core/retry_schedule.hpp"
#include "mocaplink/sources/descriptor.hpp"
#include "mocaplink/sources/loop_thread.hpp"
#include "mocaplink/sources/source.hpp"
#include "mocaplink/sources/vrpn_options.hpp"

namespace mocaplink::sources {

struct VrpnSourceOptions {
  VrpnOptions target;
  /// When to try again after losing the server: at once (50 ms), then every 200 ms for 5 s, then
  /// doubling to 5 s (core/retry_schedule.hpp); back to the start once a connection worked.
  core::RetryPolicy retry{};
  std::chrono::milliseconds connect_timeout{5000};
};

/// VRPN-specific counters, beyond SourceCounters; read from any thread.
struct VrpnCounters {
  std::atomic<std::uint64_t> messages{0};        ///< messages read (all types)
  std::atomic<std::uint64_t> bytes{0};           ///< bytes read
  std::atomic<std::uint64_t> connections{0};     ///< cookie exchanges completed
  std::atomic<std::uint64_t> reports{0};         ///< Pos_Quat reports of wanted trackers
  std::atomic<std::uint64_t> other_trackers{0};  ///< Pos_Quat reports of trackers not asked for
  std::atomic<std::uint64_t> unknown_ids{0};     ///< messages from undescribed senders or types
  std::atomic<std::uint64_t> frozen{0};          ///< reports made untracked: pose held still
  std::atomic<std::uint64_t> timeouts{0};        ///< connections dropped for silence
};

class VrpnSource final : public Source {
 public:
  VrpnSource(VrpnSourceOptions options, std::string url);
  ~VrpnSource() override;

  /// Spawns the client thread; callbacks run on it. Call once.
  void start(FrameSink on_frame, StateSink on_state) override;
  /// Closes the connection and joins; no callback runs after it returns. Idempotent.
  void stop() override;
  [[nodiscard]] std::string url() const override { return url_; }
  [[nodiscard]] const SourceCounters& counters() const override { return counters_; }
  [[nodiscard]] const VrpnCounters& vrpn_counters() const { return vrpn_counters_; }
  /// The most recent connection error or dropped-message reason ("" if none); any thread.
  [[nodiscard]] std::string last_error() const;
  /// Tracker names the server described on the current or last connection; any thread.
  [[nodiscard]] std::vector<std::string> trackers() const;

 private:
  class Session;  // Asio state, lives on the client thread (vrpn_source.cpp)
  friend class Session;

  VrpnSourceOptions options_;
  std::string url_;
  SourceCounters counters_;
  VrpnCounters vrpn_counters_;
  mutable std::mutex mutex_;
  std::string last_error_;             // guarded by mutex_
  std::vector<std::string> trackers_;  // guarded by mutex_
  LoopThread<Session> worker_;         // last: stopped first
};

/// vrpn:// for the source registry: parse_vrpn_options, a VrpnSource, and the VrpnServer emulator
/// for `serve --protocol vrpn`.
[[nodiscard]] SourceDescriptor vrpn_source_descriptor();

}  // namespace mocaplink::sources
