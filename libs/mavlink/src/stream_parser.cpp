// Stream parser: frame boundaries in untrusted bytes, resync, counters (mavlink-wire.md §8).
#include "mocaplink/mavlink/stream_parser.hpp"

#include <algorithm>
#include <cstring>

#include "frame_layout.hpp"

namespace mocaplink::mavlink {
namespace {

bool is_magic(std::uint8_t b) noexcept {
  return b == kMagicV2 || b == kMagicV1;
}

/// A complete, CRC-valid frame of a known message starts at bytes[0].
bool known_valid_frame_at(std::span<const std::uint8_t> bytes) noexcept {
  const auto size = detail::announced_size(bytes);
  if (!size || *size == 0 || *size > bytes.size()) return false;
  const FrameView v = detail::view_frame(bytes.first(*size));
  return v.info != nullptr && detail::crc_matches(v);
}

}  // namespace

std::size_t StreamParser::append(std::span<const std::uint8_t> bytes) noexcept {
  const std::size_t n = std::min(bytes.size(), buffer_.size() - size_);
  std::memcpy(buffer_.data() + size_, bytes.data(), n);
  size_ += n;
  return n;
}

std::optional<FrameView> StreamParser::next_buffered(std::uint64_t now_10us) noexcept {
  bool truncated = false;
  return next_in(std::span<const std::uint8_t>(buffer_.data(), size_), start_, false, truncated,
                 now_10us);
}

void StreamParser::compact() noexcept {
  if (start_ == 0) return;
  std::memmove(buffer_.data(), buffer_.data() + start_, size_ - start_);
  size_ -= start_;
  start_ = 0;
}

bool StreamParser::policy_accepts(const FrameView& frame, std::uint64_t now_10us) noexcept {
  if (verifier_ == nullptr) return true;
  const SignatureVerdict verdict =
      verifier_->check(frame.bytes, frame.msgid, frame.sysid, frame.compid, now_10us);
  switch (verdict) {
    case SignatureVerdict::accepted_signed:
    case SignatureVerdict::accepted_unsigned:
      return true;
    case SignatureVerdict::bad_signature:
      ++counters_.bad_signature;
      break;
    case SignatureVerdict::replay:
      ++counters_.replay;
      break;
    case SignatureVerdict::stale_new_stream:
      ++counters_.stale_new_stream;
      break;
    case SignatureVerdict::unsigned_rejected:
      ++counters_.unsigned_rejected;
      break;
    case SignatureVerdict::too_many_streams:
      ++counters_.too_many_streams;
      break;
  }
  return false;
}

std::optional<FrameView> StreamParser::next_in(std::span<const std::uint8_t> bytes,
                                               std::size_t& pos, bool final, bool& truncated,
                                               std::uint64_t now_10us) noexcept {
  while (pos < bytes.size()) {
    // Search the next magic; everything before it is garbage.
    const auto rest = bytes.subspan(pos);
    const auto magic = std::find_if(rest.begin(), rest.end(), is_magic);
    const auto skipped = static_cast<std::size_t>(magic - rest.begin());
    counters_.garbage_bytes += skipped;
    pos += skipped;
    if (pos == bytes.size()) return std::nullopt;

    const auto candidate = bytes.subspan(pos);
    const auto size = detail::announced_size(candidate);
    if (!size || *size > candidate.size()) {
      if (!final) return std::nullopt;  // wait for the rest of the frame
      // No more bytes will come: reject this magic and look for complete frames after it.
      truncated = true;
      ++pos;
      continue;
    }
    const FrameView view = detail::view_frame(candidate.first(*size));
    const bool crc_ok = view.info != nullptr && detail::crc_matches(view);
    if ((view.incompat_flags & ~kIncompatSigned) != 0) {
      // §4: drop. A valid CRC proves the frame real (skip it whole); otherwise resync after the
      // magic like any rejected candidate.
      ++counters_.unknown_incompat;
      pos += crc_ok ? *size : 1;
      continue;
    }
    if (view.info != nullptr && !crc_ok) {
      ++counters_.bad_crc;
      ++pos;  // §8: resume one byte after the rejected magic
      continue;
    }
    if (view.info == nullptr) {
      // Unknown id: the CRC cannot be checked. If a verifiable known frame starts inside the
      // claimed extent, this "frame" is more likely a fake magic: let the known frame win.
      bool hides_valid_frame = false;
      for (std::size_t i = 1; i < *size && !hides_valid_frame; ++i) {
        hides_valid_frame = is_magic(candidate[i]) && known_valid_frame_at(candidate.subspan(i));
      }
      if (hides_valid_frame) {
        ++counters_.garbage_bytes;
        ++pos;
        continue;
      }
    }
    pos += *size;
    if (!policy_accepts(view, now_10us)) continue;
    ++counters_.frames;
    if (view.version == 1) ++counters_.v1_frames;
    if (view.is_signed()) ++counters_.signed_frames;
    if (view.info == nullptr) ++counters_.unknown_msgid;
    return view;
  }
  return std::nullopt;
}

}  // namespace mocaplink::mavlink
