// PosesFirst: when a frame forwarded from a ground station may go out on a link that also carries
// the vehicle's poses (issue 38; docs/daemon.md "Ground stations on the vehicle's link").
//
// mocaplink's own frames (poses, its heartbeat, TIMESYNC, the set-up's requests) are written the
// moment they are made. Forwarded frames wait here, in a bounded queue (full: the new frame is
// dropped and counted), and one is handed out only when it cannot delay the next pose:
//   * the link's own write queue is empty (the caller asks only then);
//   * on a link of known speed (a serial port: baud / 10 bytes a second), the frame would be on
//     the wire completely before the next pose is due — the UART is modelled as busy until every
//     byte written so far has left, and the next pose as due one pose period after the last own
//     write, less a tenth of a period for the mocap's jitter. When no own frame has been written
//     for 1.5 periods (no mocap frames, the vehicle paused), nothing is due and the queue flows.
// A link of unknown speed (TCP) gets only the first rule.
// The model never runs ahead of reality for long, nor behind it: it holds at most a tty's output
// buffer (kModelCapBytes) of air time — a pty or a USB serial port takes bytes faster than its
// nominal baud, so an overload must not make the model owe seconds —, and what the OS says it
// still holds (TIOCOUTQ) can only make it later, never earlier (a pty reads 0 while the radio
// behind it is still busy). A forwarded frame older than max_age is dropped and counted, never
// sent: a ground station repeats what it still wants, and a command delivered seconds late (an ARM)
// must not arrive at all. Pure: time is passed in. Not thread-safe (one owner, the link's loop
// thread).
#pragma once

#include <chrono>
#include <cstddef>
#include <cstdint>
#include <deque>
#include <optional>
#include <span>
#include <vector>

#include "mocaplink/core/time.hpp"

namespace mocaplink::io {

class PosesFirst {
 public:
  struct Options {
    double bytes_per_second = 0.0;  ///< the link's speed; 0: unknown (no air-time rule)
    std::size_t max_queue_bytes = 4096;
    std::chrono::nanoseconds max_age = std::chrono::seconds(1);
  };
  struct Counters {
    std::uint64_t queued = 0;         ///< forwarded frames accepted into the queue
    std::uint64_t handed_out = 0;     ///< given to the link to write
    std::uint64_t dropped_full = 0;   ///< refused: the queue was full
    std::uint64_t dropped_stale = 0;  ///< waited longer than max_age: dropped, never sent
    std::uint64_t bytes_handed_out = 0;
    std::uint64_t own_bytes = 0;  ///< mocaplink's own bytes written (the poses' share)
  };

  /// The modelled backlog never exceeds this many bytes of air time: a tty's output buffer.
  static constexpr std::size_t kModelCapBytes = 4096;

  explicit PosesFirst(Options options);

  /// The vehicle's pose period (1 / rate_hz); zero: unknown (no pose rule).
  void set_pose_period(std::chrono::nanoseconds period) { pose_period_ = period; }
  /// One of mocaplink's own frames, `bytes` long, was written at `now`.
  void on_own_write(std::size_t bytes, core::HostTime now);
  /// A forwarded frame, arrived at `now`, waits its turn; false when the queue is full (dropped,
  /// counted).
  bool push(std::span<const std::uint8_t> frame, core::HostTime now);
  /// The OS still holds `bytes` of what was written (TIOCOUTQ): the UART is busy at least that
  /// long.
  void observe_unsent(std::size_t bytes, core::HostTime now);
  /// The link's own queue is empty at `now`: the next forwarded frame to write, or nullopt —
  /// then, if frames wait, `retry_at` says when to ask again. The frame is taken out of the queue.
  [[nodiscard]] std::optional<std::vector<std::uint8_t>> next(core::HostTime now,
                                                              core::HostTime& retry_at);
  [[nodiscard]] bool empty() const noexcept { return queue_.empty(); }
  [[nodiscard]] std::size_t queued_bytes() const noexcept { return queued_bytes_; }
  [[nodiscard]] const Counters& counters() const noexcept { return counters_; }
  /// Drops what waits (connection lost); returns how many frames.
  std::uint64_t clear() noexcept;

 private:
  [[nodiscard]] std::chrono::nanoseconds air_time(std::size_t bytes) const;
  void occupy(std::size_t bytes, core::HostTime now);

  Options options_;
  std::chrono::nanoseconds pose_period_{0};
  std::optional<core::HostTime> last_own_;
  core::HostTime busy_until_{};  // the modelled UART's last byte leaves then
  struct Waiting {
    std::vector<std::uint8_t> frame;
    core::HostTime since;
  };
  std::deque<Waiting> queue_;
  std::size_t queued_bytes_ = 0;
  Counters counters_;
};

}  // namespace mocaplink::io
