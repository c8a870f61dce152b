// RateWindow: how often something happened recently (a vehicle's pose sends), measured over a
// fixed window of host time ending at whatever moment it is asked, so the figure does not depend
// on who asks or when they asked before (issue 29: a rate measured between two dashboard requests
// read 0 Hz on the first request). The Station's frame rate uses the same formula:
//
//   rate_hz(now) = (n − 1) / (now − oldest)   for the n events at times in (now − window, now]
//
// 0 with fewer than two events. Right after a start (events for less than a window) it is the rate
// so far: 26 events 20 ms apart asked 500 ms after the first read 50 Hz. When events stop it falls
// smoothly to 0 within one window. Asked between two events it reads up to one event low
// (49 of 50 Hz), never high.
//
// Memory: the times of the last window's events in a Ring, at most `max_events` (older ones are
// forgotten even inside the window: the rate then reads low, only at rates above max_events per
// window). add() does not allocate once the ring has held a window's events. Times passed to add()
// must not go backwards (one steady clock). Pure; not thread-safe (one owner).
#pragma once

#include <chrono>
#include <cstddef>
#include <cstdint>

#include "mocaplink/core/ring.hpp"
#include "mocaplink/core/time.hpp"

namespace mocaplink::core {

class RateWindow {
 public:
  /// `window` > 0; `max_events` ≥ 2 (a programming error otherwise: aborts).
  explicit RateWindow(Duration window = std::chrono::seconds(1), std::size_t max_events = 4096);

  /// One event at host time `t`.
  void add(HostTime t);
  /// Events per second over (now − window, now]; see the header comment.
  [[nodiscard]] double rate_hz(HostTime now) const;
  [[nodiscard]] Duration window() const { return window_; }

 private:
  Duration window_;
  std::size_t max_events_;
  Ring<HostTime> times_;  // oldest first
};

/// `events` spread over `elapsed`, per second: a whole run's average (the daemon's final summary),
/// as opposed to RateWindow's recent rate. 0 when `elapsed` is not positive.
[[nodiscard]] double average_rate_hz(std::uint64_t events, Duration elapsed);

}  // namespace mocaplink::core
