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
#include <string>

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

/// Counters every source keeps; read from any thread.
struct SourceCounters {
  std::atomic<std::uint64_t> frames{0};      ///< frames delivered to the sink
  std::atomic<std::uint64_t> malformed{0};   ///< packets/messages dropped as malformed
  std::atomic<std::uint64_t> reconnects{0};  ///< connection attempts after the first
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
