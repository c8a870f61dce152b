// Alerts derived from a StatusView (the dashboard's alert list and the `alerts` of the API):
//
//   kind                   level    when
//   source_disconnected    error    the Station is not connected to its source
//   body_lost              warning  a body is LOST (error when a vehicle follows it)
//   body_mirrored          warning  a body's rotation from the source is a reflection (a
//                                   left-handed matrix; error when a vehicle follows it)
//   link_down              error    a vehicle's link cannot send
//   vehicle_silent         warning  nothing heard from a vehicle (its link state is silent)
//   origin_not_confirmed   warning  still sending SET_GPS_GLOBAL_ORIGIN, not confirmed yet
//   origin_conflict        error    ArduPilot holds another origin (changes only on reboot)
//   agreement_failing      error    the vehicle's own estimate disagrees with the mocap estimate
//   drops_rising           warning  the Station's dropped count grew within the last
//                                   drops_window_s seconds
#pragma once

#include <cstdint>
#include <deque>
#include <utility>

#include "mocaplink/web/status.hpp"

namespace mocaplink::web {

struct AlertRules {
  double drops_window_s = 10.0;  ///< > 0; how far back "drops rising" looks
};

/// Remembers the dropped counter over the last window. Not thread-safe: the server calls it
/// under its own lock. Time is passed in (seconds on any monotonic clock).
class AlertMonitor {
 public:
  explicit AlertMonitor(AlertRules rules = {});

  /// Appends the alerts derived from `status` (at time `now_s`) to status.alerts, after the ones
  /// already there. A `now_s` that goes backwards is treated as equal to the previous one.
  void annotate(StatusView& status, double now_s);

 private:
  AlertRules rules_;
  std::deque<std::pair<double, std::uint64_t>> dropped_history_;  // (time s, dropped), oldest first
};

}  // namespace mocaplink::web
