// Vicon Tracker UDP datagrams → MocapFrames, pure (vicon-tracker-udp.md §3–§5).
//
//   - frame_number is the Vicon frame number unwrapped to 64 bits (a u32 wrap is counted);
//     frame_step is the smallest forward step seen so far, so that a stream slower than the
//     cameras (numbers 2 apart) does not count every other number as a lost frame.
//   - A datagram older than the newest accepted one by at most kMaxLateFrames is late: dropped and
//     counted. Further back is a Tracker restart: numbering starts again from it.
//   - A datagram with the newest frame number again (a frame split over several datagrams) gives
//     the frame again with the objects of both, at the first one's capture time.
//   - capture_time is the host arrival time (the stream has no time stamp) smoothed by
//     ArrivalClock with the frame-number step × the frame period learned from the stream itself
//     (the median arrival gap per frame number over the last 15 datagrams, from the 4th on).
//   - An object is untracked when its six values are all 0.0 or have stayed bit-identical for more
//     than `frozen` datagrams; absent objects are simply not in the frame.
//   - Positions mm → m; rotation by the configured Euler order.
//   - on_silence: one frame with every body seen untracked (same frame number, counted by the
//     Station as a repeat), then nothing until datagrams resume.
#pragma once

#include <cstdint>
#include <deque>
#include <optional>
#include <span>
#include <string>
#include <unordered_map>
#include <vector>

#include "mocaplink/core/mocap_frame.hpp"
#include "mocaplink/core/time.hpp"
#include "mocaplink/wire/arrival_clock.hpp"
#include "mocaplink/wire/vicon_udp.hpp"

namespace mocaplink::wire::vicon_udp {

inline constexpr std::int64_t kMaxLateFrames = 1000;
/// Distinct object names remembered (for frozen detection and the loss frame).
inline constexpr std::size_t kMaxObjects = 1024;

struct StreamConfig {
  EulerOrder rotation = EulerOrder::xyz;
  std::uint32_t frozen = 10;  ///< 0 = never
  double max_abs_mm = 1e6;
};

struct StreamCounters {
  std::uint64_t datagrams = 0;
  std::uint64_t malformed = 0;
  std::uint64_t padded = 0;  ///< datagrams with zero bytes after the items (Tracker's blocks)
  std::uint64_t late = 0;
  std::uint64_t wraps = 0;
  std::uint64_t restarts = 0;
  std::uint64_t split_frames = 0;  ///< datagrams repeating the newest frame number
  std::uint64_t unknown_items = 0;
  std::uint64_t untracked = 0;  ///< objects made untracked (zeros or frozen)
  std::uint64_t gaps = 0;       ///< frame-number steps larger than frame_step
};

class Stream {
 public:
  explicit Stream(StreamConfig config = {}) : config_(config) {}

  /// One datagram, arrived at `arrival`: the frame to deliver, nothing (late), or the parse error
  /// (counted as malformed).
  [[nodiscard]] Result<std::optional<core::MocapFrame>> on_datagram(
      std::span<const std::byte> bytes, core::HostTime arrival);
  /// No datagram for the configured silence: the loss frame (once), else nothing.
  [[nodiscard]] std::optional<core::MocapFrame> on_silence(core::HostTime now);

  [[nodiscard]] const StreamCounters& counters() const { return counters_; }

 private:
  struct Seen {
    std::array<double, 6> values{};
    std::uint32_t repeats = 0;
  };
  core::BodySample sample(const Object& o);
  core::SourceTime capture_at(core::HostTime host, std::int64_t frames_since_last);

  StreamConfig config_;
  StreamCounters counters_;
  std::optional<std::uint32_t> last_raw_;
  std::uint64_t unwrapped_ = 0;
  std::uint32_t step_ = 0;                   // 0 until a forward step was seen
  std::optional<core::MocapFrame> current_;  // the newest frame delivered
  ArrivalClock clock_;
  // Arrival gaps per frame number of the recent datagrams, for the frame period.
  static constexpr std::size_t kPeriodSamples = 15;
  std::deque<core::Duration> gaps_;
  std::optional<core::HostTime> last_arrival_;
  bool lost_sent_ = true;
  std::unordered_map<std::string, Seen> seen_;
  std::vector<std::string> names_;  // in order of first appearance
};

}  // namespace mocaplink::wire::vicon_udp
