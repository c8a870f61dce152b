// Internal: reading the fixed header layout of MAVLink 1/2 frames (mavlink-wire.md §1) once the
// caller has established that `bytes` holds at least the frame size announced by its header.
#pragma once

#include <cstddef>
#include <cstdint>
#include <optional>
#include <span>

#include "mocaplink/mavlink/frame.hpp"

namespace mocaplink::mavlink::detail {

/// Size of the frame at bytes[0] from its first bytes: 0 if bytes[0] is not a magic, nullopt if
/// bytes are too few to tell (v2 needs magic, len, incompat_flags; v1 needs magic, len).
inline std::optional<std::size_t> announced_size(std::span<const std::uint8_t> bytes) noexcept {
  if (bytes.empty()) return std::nullopt;
  if (bytes[0] == kMagicV2) {
    if (bytes.size() < 3) return std::nullopt;
    const bool is_signed = (bytes[2] & kIncompatSigned) != 0;
    return kHeaderSizeV2 + bytes[1] + kChecksumSize + (is_signed ? kSignatureSize : 0);
  }
  if (bytes[0] == kMagicV1) {
    if (bytes.size() < 2) return std::nullopt;
    return kHeaderSizeV1 + bytes[1] + kChecksumSize;
  }
  return std::size_t{0};
}

/// Fills a FrameView from `frame`, whose size must equal announced_size(frame) (checked by the
/// caller). Looks up the message info; does not check the CRC.
FrameView view_frame(std::span<const std::uint8_t> frame) noexcept;

/// CRC over the frame (after the magic, through the payload) plus the message's crc_extra equals
/// the received checksum. Requires view.info != nullptr.
bool crc_matches(const FrameView& view) noexcept;

}  // namespace mocaplink::mavlink::detail
