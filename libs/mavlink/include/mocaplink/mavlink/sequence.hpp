// Sequence numbers of one sending identity (mavlink-wire.md §5): one counter per (sysid, compid)
// mocaplink sends as, incremented per frame and wrapping 255 → 0. Not one global counter: the
// original ViconMAVLink shared one across vehicles, so each vehicle saw artificial gaps.
#pragma once

#include <cstdint>

#include "mocaplink/mavlink/frame.hpp"

namespace mocaplink::mavlink {

/// Sender side: hands out FrameHeaders with consecutive seq for one (sysid, compid). Not
/// thread-safe (one sender owns it).
class SequenceCounter {
 public:
  constexpr SequenceCounter(std::uint8_t sysid, std::uint8_t compid,
                            std::uint8_t first_seq = 0) noexcept
      : sysid_(sysid), compid_(compid), next_(first_seq) {}

  /// Header for the next frame; advances seq (255 wraps to 0).
  [[nodiscard]] constexpr FrameHeader next() noexcept {
    return FrameHeader{.seq = next_++, .sysid = sysid_, .compid = compid_};
  }
  /// The seq the next frame will carry.
  [[nodiscard]] constexpr std::uint8_t peek_seq() const noexcept { return next_; }
  [[nodiscard]] constexpr std::uint8_t sysid() const noexcept { return sysid_; }
  [[nodiscard]] constexpr std::uint8_t compid() const noexcept { return compid_; }

 private:
  std::uint8_t sysid_;
  std::uint8_t compid_;
  std::uint8_t next_;
};

}  // namespace mocaplink::mavlink
