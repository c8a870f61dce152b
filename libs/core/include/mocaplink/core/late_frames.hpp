// LateFrames: whether a mocap frame is still worth turning into poses when the event loop gets to
// it (issues 15 and 27). Neither autopilot can be told to expect an old pose: EKF2_EV_DELAY is at
// most 300 ms and VISO_DELAY_MS at most 250 ms, and PX4 without timesync takes a pose as of its
// arrival (protocols/autopilots.md §4). A frame can be old for two reasons:
// - it waited in the hand-over queue between its source's thread and the loop, normally for
//   microseconds; when the machine cannot keep up (more vehicles than its cores can send to, or a
//   stall) the wait grows to the whole queue (256 frames, about 1 s at 240 Hz);
// - its source delivered it late: a TCP backlog after a network stall, a VRPN round completed only
//   when a tracker's report finally came, a replay behind its schedule. Such a frame arrives now
//   but was captured long ago (Bridge::frame_age says how long, from the source's own clock).
// So a frame older than kMaxFrameWait when the loop takes it is skipped and counted, and the loop
// goes on with the fresher frames behind it: the poses that do leave stay young.
// Before that limit comes into play, a loop that is behind finds several frames waiting at once
// (issue 30). Working through them in order would send every pose as late as the backlog is long,
// up to the 250 ms limit, where a machine short of CPU can still send the newest pose fresh. So
// once the loop is behind — it took a frame that had waited more than catch_up_after() since its
// source handed it over, and it has not been idle since — a frame with a newer one already waiting
// behind it that has a sample of each of its bodies (supersedes) and that arrived after it, not
// with it (kSameBurst: the loop was behind, not the source bursting) is superseded: not tracked,
// not sent, counted apart from the late ones. The loop is caught up again when a frame finds it
// idle (is handed over after the loop finished the batch before). A loop that is late by less than
// that limit for a moment (a scheduling hiccup, one slow frame, a machine near but not past its
// limit) sends every frame, a few ms late, as it did before superseding: what is lost is only what
// the CPU cannot do, not what a hiccup delayed. The limit is kCatchUpAfter, or kCatchUpPeriods
// frame periods where that is longer (below 200 Hz; at 100 Hz 10 ms is a single period, and a loop
// one frame late would supersede the frame it was late with), at most kMaxCatchUpAfter; the
// period is the interval between the frames' capture times (FrameInterval, as the Sender observes
// it), from the frames the loop reports (observe).
// Once behind, it stays so until it idles, so a saturated loop keeps sending only the newest pose
// however small its backlog of the moment is. Frames of one burst (a TCP read of several frames, a
// VRPN round, a replay catching up) reach the loop together however idle it is, so none of them
// supersedes another: each is sent, or judged late by its capture time; otherwise a source that
// routinely delivers frames in pairs would lose half its poses on a busy machine, and the count
// would blame the CPU for it. Skipped, not folded into the trackers without sends: under overload
// the CPU is what is short, and the trackers are a large part of a frame's work, so folding would
// spend it on poses nobody gets and keep the loop behind; a tracker sees the longer step as it sees
// a dropped frame (its prediction and gate widen with the step); and a replay, which skips what the
// run did not send, then feeds its trackers exactly what the run's had (docs/daemon.md).
// Pure; time is passed in; one owner (the event loop).
#pragma once

#include <chrono>
#include <cstdint>
#include <optional>

#include "mocaplink/core/frame_interval.hpp"
#include "mocaplink/core/mocap_frame.hpp"
#include "mocaplink/core/time.hpp"

namespace mocaplink::core {

/// The oldest a frame may be when the loop takes it (since its capture, or since its arrival where
/// the capture cannot be placed on the host clock) and still be sent.
inline constexpr Duration kMaxFrameWait = std::chrono::milliseconds(250);
/// Frames that arrived within this of each other came in one burst from their source: the loop
/// could not have taken the first before the second came, so neither supersedes the other. Far
/// below any mocap frame period (1 ms at 1000 Hz), far above a burst's spacing (microseconds).
inline constexpr Duration kSameBurst = std::chrono::microseconds(500);
/// The loop is behind, and supersedes frames, once it takes a frame that waited longer than this
/// for it, or kCatchUpPeriods frame periods where that is longer (LateFrames::catch_up_after), and
/// until a frame finds it idle. Above the few ms a busy machine that keeps up delays a
/// frame now and then (docs/performance.md: at 500 vehicles on 2 cores the poses' p99, queue and
/// sends together, is 5-7 ms), below the 20-50 ms a vision delay is usually set to.
inline constexpr Duration kCatchUpAfter = std::chrono::milliseconds(10);
/// Below 200 Hz the limit is this many frame periods instead (20 ms at 100 Hz), so that a loop
/// one frame late for a moment is not behind, from 40 Hz up (kMaxCatchUpAfter).
inline constexpr int kCatchUpPeriods = 2;
/// The most the limit grows to at low rates (50 ms is reached at 40 Hz): the upper end of the
/// vision delays autopilots are usually set to, and a fifth of kMaxFrameWait.
inline constexpr Duration kMaxCatchUpAfter = std::chrono::milliseconds(50);
/// Skipped frames are warned about at most this often (the first at once).
inline constexpr Duration kLateWarningPeriod = std::chrono::seconds(10);

/// Whether `newer`, a frame that arrived after `older`, makes `older` not worth tracking and
/// sending: it has a sample of every body `older` has (tracked or not: the newer word on a body is
/// the one that counts), in any order. A frame that lacks one of `older`'s bodies (a source that
/// sends some bodies in one frame and the others in the next) does not supersede it.
[[nodiscard]] bool supersedes(const MocapFrame& newer, const MocapFrame& older) noexcept;

/// Frames not sent since the previous warning.
struct LateWarning {
  std::uint64_t skipped = 0;     ///< how many were late
  Duration oldest{};             ///< the age of the oldest late one when it was skipped
  std::uint64_t superseded = 0;  ///< how many were superseded by a newer one waiting
};

class LateFrames {
 public:
  /// `max_wait` ≥ 0 (0: every frame that waited at all is late).
  explicit LateFrames(Duration max_wait = kMaxFrameWait) noexcept : max_wait_(max_wait) {}

  /// True when a frame `age` old (Bridge::frame_age) is older than max_wait: the caller skips
  /// it, and it is counted. Exactly max_wait is still in time.
  [[nodiscard]] bool skip_if_late(Duration age) noexcept;
  /// skip_if_late for a frame whose age is the time since it was received (no capture time).
  [[nodiscard]] bool skip_if_late(HostTime received, HostTime now) noexcept {
    return skip_if_late(now - received);
  }
  /// The loop took `frame` from the queue: it reports each one, in order, before begin_batch.
  /// The interval between their capture times (FrameInterval) is the frame period.
  void observe(const MocapFrame& frame) noexcept { interval_.observe(frame.capture_time); }
  /// How long a frame may wait for the loop before the loop counts as behind: kCatchUpAfter, or
  /// kCatchUpPeriods frame periods if that is longer, at most kMaxCatchUpAfter.
  [[nodiscard]] Duration catch_up_after() const noexcept;
  /// The loop takes a batch at `now`, whose oldest frame its source handed over at `first_queued`:
  /// it is behind from now on if that frame waited longer than catch_up_after(), and caught up if
  /// that frame was handed over after the previous batch was done (end_batch): the loop was idle.
  void begin_batch(HostTime first_queued, HostTime now) noexcept;
  /// The loop is done with the batch (sent, skipped, recorded) at `now`.
  void end_batch(HostTime now) noexcept { batch_done_ = now; }
  /// Whether the loop is behind (begin_batch): only then are frames superseded.
  [[nodiscard]] bool behind() const noexcept { return behind_; }
  /// True when the loop is behind and `next`, the frame taken from the queue right after `frame`,
  /// supersedes it and arrived more than kSameBurst after it (`received`, `next_received`: host
  /// arrival times): the caller skips `frame`, counted as superseded.
  [[nodiscard]] bool skip_if_superseded(const MocapFrame& frame, HostTime received,
                                        const MocapFrame& next, HostTime next_received) noexcept;
  /// Frames skipped as late since construction.
  [[nodiscard]] std::uint64_t skipped() const noexcept { return skipped_; }
  /// Frames skipped as superseded since construction.
  [[nodiscard]] std::uint64_t superseded() const noexcept { return superseded_; }
  /// What to warn about at `now`, if anything was skipped (late or superseded) since the previous
  /// warning and that warning is kLateWarningPeriod old (the first skip is warned about at once);
  /// then starts counting afresh.
  [[nodiscard]] std::optional<LateWarning> warning(HostTime now) noexcept;

 private:
  Duration max_wait_;
  std::uint64_t skipped_ = 0;
  std::uint64_t superseded_ = 0;
  LateWarning pending_;                 // since the previous warning
  std::optional<HostTime> warned_;      // when the previous warning was given
  std::optional<HostTime> batch_done_;  // when the loop was done with its previous batch
  bool behind_ = false;                 // since a frame waited > catch_up_after(); until one idles
  FrameInterval interval_;              // between the frames' capture times (observe)
};

}  // namespace mocaplink::core
