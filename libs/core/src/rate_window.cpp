// RateWindow (rate_window.hpp): events per second over a fixed recent window.
#include "mocaplink/core/rate_window.hpp"

#include <cstdio>
#include <cstdlib>

namespace mocaplink::core {

RateWindow::RateWindow(Duration window, std::size_t max_events)
    : window_(window), max_events_(max_events) {
  if (window <= Duration::zero() || max_events < 2) {
    std::fprintf(stderr, "mocaplink::core::RateWindow: invalid window or max_events (%zu)\n",
                 max_events);
    std::abort();
  }
}

void RateWindow::add(HostTime t) {
  times_.push_back(t);
  while (times_.size() > max_events_ || times_.front() <= t - window_) times_.pop_front();
}

double RateWindow::rate_hz(HostTime now) const {
  std::size_t n = 0;
  HostTime oldest{};
  for (std::size_t i = 0; i < times_.size(); ++i) {
    const HostTime t = times_[i];
    if (t <= now - window_ || t > now) continue;
    if (n == 0) oldest = t;
    ++n;
  }
  if (n < 2 || now <= oldest) return 0.0;
  return static_cast<double>(n - 1) / to_seconds(now - oldest);
}

double average_rate_hz(std::uint64_t events, Duration elapsed) {
  if (elapsed <= Duration::zero()) return 0.0;
  return static_cast<double>(events) / to_seconds(elapsed);
}

}  // namespace mocaplink::core
