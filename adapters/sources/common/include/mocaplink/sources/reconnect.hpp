// What every reconnecting network source shares (DESIGN.md "Fault behaviour": reconnect with
// back-off): its connection state reported once per change — every `disconnected` is reported,
// each with its own reason — and the delay before the next attempt, doubling up to a maximum and
// back to the start once a connection worked. Used on the source's own thread.
#pragma once

#include <algorithm>
#include <chrono>
#include <string>
#include <utility>

#include "mocaplink/sources/source.hpp"

namespace mocaplink::sources {

class StateReporter {
 public:
  explicit StateReporter(StateSink sink) : sink_(std::move(sink)) {}
  void operator()(SourceState state, const std::string& detail) {
    if (state == state_ && state != SourceState::disconnected) return;
    state_ = state;
    if (sink_) sink_(state, detail);
  }

 private:
  StateSink sink_;
  SourceState state_ = SourceState::disconnected;
};

class Backoff {
 public:
  Backoff(std::chrono::milliseconds initial, std::chrono::milliseconds max)
      : initial_(initial), max_(max), next_(initial) {}
  /// The delay before the next attempt; the one after it is twice as long (at most max).
  [[nodiscard]] std::chrono::milliseconds next() {
    const auto now = next_;
    next_ = std::min(next_ * 2, max_);
    return now;
  }
  /// A connection worked: the next failure waits `initial` again.
  void reset() { next_ = initial_; }

 private:
  std::chrono::milliseconds initial_;
  std::chrono::milliseconds max_;
  std::chrono::milliseconds next_;
};

}  // namespace mocaplink::sources
