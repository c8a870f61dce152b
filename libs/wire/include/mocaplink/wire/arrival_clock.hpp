// Capture times for sources whose frames carry no usable time stamp of the capture (VRPN, the Vicon
// Tracker UDP stream): the host arrival time is the only absolute time, but a thread that was not
// scheduled for a few milliseconds receives several frames at once, and a filter fed their arrival
// times sees absurd velocities. The source's own count of time between frames (VRPN's wall-clock
// stamps, Vicon frame numbers × the learned frame period) is unaffected by that, so:
//
//   capture = previous capture + source step, moved 1/32 of the way toward the arrival time;
//
// the arrival time itself when there is no previous capture, no source step, a step outside
// (0, 1 s], or when the two differ by more than 0.5 s (a silence, a restart). Capture times
// strictly increase. Pure; one per connection or stream.
#pragma once

#include <chrono>
#include <optional>

#include "mocaplink/core/time.hpp"

namespace mocaplink::wire {

class ArrivalClock {
 public:
  /// The capture time of a frame that arrived at `arrival`, `source_step` after the previous one
  /// by the source's own clock (nullopt: unknown).
  [[nodiscard]] core::SourceTime next(core::HostTime arrival,
                                      std::optional<core::Duration> source_step) {
    using namespace std::chrono_literals;
    const auto a = core::source_time_from_ns(arrival.time_since_epoch().count());
    core::SourceTime capture = a;
    if (last_ && source_step && *source_step > core::Duration::zero() && *source_step <= 1s) {
      const core::SourceTime predicted = *last_ + *source_step;
      const core::Duration error = a - predicted;
      if (error < 500ms && error > -500ms) capture = predicted + error / 32;
    }
    if (last_ && capture <= *last_) capture = *last_ + 1us;
    last_ = capture;
    return capture;
  }

 private:
  std::optional<core::SourceTime> last_;
};

}  // namespace mocaplink::wire
