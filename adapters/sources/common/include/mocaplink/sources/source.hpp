// The one interface every mocap source implements (today vicon, sim, replay, each in its own
// folder adapters/sources/<name>/). A Source owns its socket/file and, when it blocks, its own
// thread; it hands each frame to the FrameSink on that thread. The consumer (Station owner) must
// make the sink thread-safe, typically a bounded queue with an overflow counter (DESIGN.md, issue
// 5).
#pragma once

#include <atomic>
#include <cstdint>
#include <functional>
#include <memory>
#include <mutex>
#include <string>
#include <utility>

#include "mocaplink/core/mocap_frame.hpp"
#include "mocaplink/core/time.hpp"

namespace mocaplink::sources {

/// Connection state of a source, as the Station and dashboard show it.
enum class SourceState { connecting, connected, disconnected, finished };

[[nodiscard]] constexpr const char* to_string(SourceState s) {
  switch (s) {
    case SourceState::connecting:
      return "connecting";
    case SourceState::connected:
      return "connected";
    case SourceState::disconnected:
      return "disconnected";
    case SourceState::finished:
      return "finished";
  }
  return "unknown";
}

/// Called once per frame, on the source's thread. `received` is the host steady time at which
/// the frame's last byte arrived (or was generated, for sim/replay).
using FrameSink = std::function<void(core::MocapFrame frame, core::HostTime received)>;

/// Called when the connection state changes, on the source's thread.
using StateSink = std::function<void(SourceState state, const std::string& detail)>;

/// A line of text one thread sets and any reads: a source's most recent error or warning, or
/// why it last dropped a packet (SourceCounters::last_rejection).
class LastError {
 public:
  [[nodiscard]] std::string get() const {
    const std::lock_guard lock(mutex_);
    return text_;
  }
  void set(std::string text) {
    const std::lock_guard lock(mutex_);
    text_ = std::move(text);
  }

 private:
  mutable std::mutex mutex_;
  std::string text_;
};

/// Counters every source keeps; read from any thread.
struct SourceCounters {
  std::atomic<std::uint64_t> frames{0};      ///< frames delivered to the sink
  std::atomic<std::uint64_t> malformed{0};   ///< packets/messages dropped as malformed
  std::atomic<std::uint64_t> reconnects{0};  ///< connection attempts after the first
  /// Packets dropped for where they came from (another sender than the configured one).
  std::atomic<std::uint64_t> refused{0};
  /// Why the latest malformed or refused packet was dropped ("" if the source does not say):
  /// `bodies`, `record`, the dashboard and the daemon's log show it next to rejected().
  LastError last_rejection;

  /// Packets dropped unread, malformed or refused: the count those commands show.
  [[nodiscard]] std::uint64_t rejected() const { return malformed + refused; }
};

class Source {
 public:
  virtual ~Source() = default;
  Source() = default;
  Source(const Source&) = delete;
  Source& operator=(const Source&) = delete;

  /// Starts delivering frames (spawns the source's thread if it has one). Call once.
  virtual void start(FrameSink on_frame, StateSink on_state) = 0;
  /// Stops and joins; no callback runs after stop() returns. Idempotent.
  virtual void stop() = 0;
  /// The URL this source was made from, for display.
  [[nodiscard]] virtual std::string url() const = 0;
  [[nodiscard]] virtual const SourceCounters& counters() const = 0;
};

}  // namespace mocaplink::sources
