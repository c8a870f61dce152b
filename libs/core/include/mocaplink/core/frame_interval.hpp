// FrameInterval: the interval between a mocap source's frames, observed from their capture times
// (the source's own clock, so how the frames travelled — in pairs from a TCP read, a round at a
// time, late — does not matter). It falls at once to a shorter interval and rises by 1/16 of the
// difference at a longer one: a dropped frame (a double interval) or a pause of the source barely
// moves it and the next frame undoes that, jitter makes it only a little smaller, and it follows a
// source whose rate really changed within a few dozen frames. A capture time not after the
// previous one is no interval: a frame handed over again (a Vicon UDP frame split over several
// datagrams comes once per datagram, with the same capture time) or a source whose clock went
// back (it restarted; the next interval counts from there).
// The Sender claims its send slots with it (half an interval early at most) and LateFrames scales
// the time a frame may wait for the loop with it. Pure; one owner.
#pragma once

#include <optional>

#include "mocaplink/core/time.hpp"

namespace mocaplink::core {

class FrameInterval {
 public:
  /// A frame captured at `capture`, in the order the source gave them.
  void observe(SourceTime capture) noexcept;
  /// The interval; none before two frames with increasing capture times.
  [[nodiscard]] std::optional<Duration> value() const noexcept { return interval_; }
  /// The capture time of the latest frame observed; none before the first.
  [[nodiscard]] std::optional<SourceTime> last() const noexcept { return last_; }

 private:
  std::optional<SourceTime> last_;
  std::optional<Duration> interval_;
};

}  // namespace mocaplink::core
