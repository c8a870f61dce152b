// Options and pacing of `replay://file.csv[?speed=1&loop=0]` (DESIGN.md "Source URLs",
// docs/sources.md "replay://").
#pragma once

#include <array>
#include <string>
#include <string_view>
#include <utility>
#include <variant>
#include <vector>

#include "mocaplink/config/url.hpp"
#include "mocaplink/core/time.hpp"

namespace mocaplink::sources {

struct ReplayOptions {
  /// The recording, as written after "replay://" (relative to the working directory, or absolute
  /// with a third slash: replay:///data/run.csv). Taken literally: no percent-decoding, no '?'.
  std::string path;
  /// Playback speed: 1 = recorded timing, 2 = twice as fast, 0 = as fast as possible (tests,
  /// batch processing); [0, 1000].
  double speed = 1.0;
  /// Start again at the end instead of finishing (frame numbers then repeat: a counter restart).
  bool loop = false;
};

/// The `replay://` query keys.
inline constexpr std::array<std::string_view, 2> kReplayOptionKeys = {"speed", "loop"};

/// A split `replay://` URL (query keys already checked against kReplayOptionKeys) → its options.
[[nodiscard]] config::ValueOrError<ReplayOptions> parse_replay_options(const config::UrlParts& url);

/// When each recorded frame is due, as an offset from the start of playback: the first frame at
/// 0, the others at (capture − first capture) / speed; at speed 0 everything is due at once.
/// Pure: ReplaySource turns offsets into host deadlines. Not thread-safe (one per playback).
class ReplaySchedule {
 public:
  /// `speed` as in ReplayOptions.
  explicit ReplaySchedule(double speed) : speed_(speed) {}
  /// Offset at which a frame captured at `capture` is due. Capture times must not decrease
  /// within one pass (the recording reader guarantees it); an earlier one is due immediately.
  [[nodiscard]] core::Duration due(core::SourceTime capture);
  /// A new pass of a looped recording begins: its first frame is due right after the last one.
  void next_pass();

 private:
  double speed_;
  // A flag and a value rather than std::optional: GCC 12 at -O2, with due() inlined into
  // ReplaySource's loop, cannot see that the optional is engaged where it is read and warns
  // -Wmaybe-uninitialized.
  bool pass_started_ = false;
  core::SourceTime first_capture_{};  ///< of the current pass; meaningful once pass_started_
  core::Duration pass_start_{0};
  core::Duration last_due_{0};
};

}  // namespace mocaplink::sources
