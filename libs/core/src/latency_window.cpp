// LatencyWindow (latency_window.hpp).
#include "mocaplink/core/latency_window.hpp"

#include <algorithm>
#include <cmath>

namespace mocaplink::core {

std::optional<LatencySummary> LatencyWindow::summary() const {
  if (count_ == 0) return std::nullopt;
  std::vector<Duration> sorted(ring_.begin(), ring_.begin() + static_cast<std::ptrdiff_t>(count_));
  std::sort(sorted.begin(), sorted.end());
  // Nearest rank: the smallest sample with at least p of the window at or below it.
  const auto rank = [&sorted](double p) {
    const auto k = static_cast<std::size_t>(std::ceil(p * static_cast<double>(sorted.size())));
    return sorted[std::max<std::size_t>(k, 1) - 1];
  };
  LatencySummary s;
  s.last = ring_[(next_ + ring_.size() - 1) % ring_.size()];
  s.p50 = rank(0.50);
  s.p99 = rank(0.99);
  s.max = sorted.back();
  s.samples = count_;
  return s;
}

}  // namespace mocaplink::core
