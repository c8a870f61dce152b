// LatencyWindow: the latest durations of something measured per frame (the bridge's own latency:
// frame received → last datagram of that frame sent) and their percentiles, for the dashboard.
// Fixed memory (the last kLatencyWindowSize samples in a ring, allocated once), no allocation in
// add(); summary() sorts a copy, so call it at dashboard rate, not per frame. Pure; one owner.
#pragma once

#include <cstddef>
#include <optional>
#include <vector>

#include "mocaplink/core/time.hpp"

namespace mocaplink::core {

/// Samples a LatencyWindow keeps (about 4 s of 240 Hz frames).
inline constexpr std::size_t kLatencyWindowSize = 1024;

struct LatencySummary {
  Duration last{};          ///< the latest sample
  Duration p50{};           ///< median of the window
  Duration p99{};           ///< 99th percentile of the window (nearest rank)
  Duration max{};           ///< largest in the window
  std::size_t samples = 0;  ///< in the window (≤ kLatencyWindowSize)
};

class LatencyWindow {
 public:
  LatencyWindow() : ring_(kLatencyWindowSize) {}

  void add(Duration sample) {
    ring_[next_] = sample;
    next_ = (next_ + 1) % ring_.size();
    if (count_ < ring_.size()) ++count_;
  }

  /// Nothing until the first sample.
  [[nodiscard]] std::optional<LatencySummary> summary() const;

 private:
  std::vector<Duration> ring_;
  std::size_t next_ = 0;
  std::size_t count_ = 0;
};

}  // namespace mocaplink::core
