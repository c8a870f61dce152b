// MAVLink frame encoding and single-frame checking (mavlink-wire.md §1–§4, §7).
#include "mocaplink/mavlink/frame.hpp"

#include <algorithm>

#include "frame_layout.hpp"
#include "mocaplink/mavlink/crc.hpp"

namespace mocaplink::mavlink {

namespace detail {

std::size_t finish_v2(std::span<std::uint8_t, kMaxFrameSize> out, std::uint32_t msgid,
                      std::uint8_t crc_extra, std::size_t max_length, const FrameHeader& header,
                      const SignParams* sign) noexcept {
  // Trailing-zero truncation ("Packet Serialization"): drop zero bytes at the end of the payload,
  // but never the first byte, so an all-zero payload keeps len = 1.
  std::size_t len = max_length;
  while (len > 1 && out[kHeaderSizeV2 + len - 1] == 0) --len;
  const bool is_signed = sign != nullptr && sign->key != nullptr;
  out[0] = kMagicV2;
  out[1] = static_cast<std::uint8_t>(len);
  out[2] = is_signed ? kIncompatSigned : 0;
  out[3] = 0;  // compat_flags: mocaplink sends 0 (§4)
  out[4] = header.seq;
  out[5] = header.sysid;
  out[6] = header.compid;
  out[7] = static_cast<std::uint8_t>(msgid & 0xFF);
  out[8] = static_cast<std::uint8_t>((msgid >> 8) & 0xFF);
  out[9] = static_cast<std::uint8_t>((msgid >> 16) & 0xFF);
  std::uint16_t crc = crc_accumulate(std::span<const std::uint8_t>(out.data() + 1, 9 + len));
  crc = crc_accumulate(crc_extra, crc);
  std::size_t size = kHeaderSizeV2 + len;
  out[size++] = static_cast<std::uint8_t>(crc & 0xFF);
  out[size++] = static_cast<std::uint8_t>(crc >> 8);
  if (!is_signed) return size;
  // Signature block (§7.1): link id, 48-bit little-endian timestamp, 6 bytes of SHA-256 over
  // key ‖ everything before the signature bytes.
  out[size++] = sign->link_id;
  const std::uint64_t ts = std::min(sign->timestamp_10us, kMaxSigningTimestamp);
  for (int i = 0; i < 6; ++i) out[size++] = static_cast<std::uint8_t>((ts >> (8 * i)) & 0xFF);
  const auto sig = sign->key->signature(std::span<const std::uint8_t>(out.data(), size));
  std::copy(sig.begin(), sig.end(), out.begin() + static_cast<std::ptrdiff_t>(size));
  return size + sig.size();
}

std::size_t finish_v1(std::span<std::uint8_t, kMaxFrameSize> out, std::uint8_t msgid,
                      std::uint8_t crc_extra, std::size_t base_length,
                      const FrameHeader& header) noexcept {
  out[0] = kMagicV1;
  out[1] = static_cast<std::uint8_t>(base_length);
  out[2] = header.seq;
  out[3] = header.sysid;
  out[4] = header.compid;
  out[5] = msgid;
  std::uint16_t crc =
      crc_accumulate(std::span<const std::uint8_t>(out.data() + 1, 5 + base_length));
  crc = crc_accumulate(crc_extra, crc);
  std::size_t size = kHeaderSizeV1 + base_length;
  out[size++] = static_cast<std::uint8_t>(crc & 0xFF);
  out[size++] = static_cast<std::uint8_t>(crc >> 8);
  return size;
}

FrameView view_frame(std::span<const std::uint8_t> frame) noexcept {
  FrameView v;
  v.bytes = frame;
  v.len = frame[1];
  std::size_t payload_at = 0;
  if (frame[0] == kMagicV2) {
    v.version = 2;
    v.incompat_flags = frame[2];
    v.compat_flags = frame[3];
    v.seq = frame[4];
    v.sysid = frame[5];
    v.compid = frame[6];
    v.msgid = static_cast<std::uint32_t>(frame[7]) | (static_cast<std::uint32_t>(frame[8]) << 8) |
              (static_cast<std::uint32_t>(frame[9]) << 16);
    payload_at = kHeaderSizeV2;
  } else {
    v.version = 1;
    v.seq = frame[2];
    v.sysid = frame[3];
    v.compid = frame[4];
    v.msgid = frame[5];
    payload_at = kHeaderSizeV1;
  }
  v.payload = frame.subspan(payload_at, v.len);
  const std::size_t crc_at = payload_at + v.len;
  v.crc = static_cast<std::uint16_t>(frame[crc_at] | (frame[crc_at + 1] << 8));
  v.info = find_message_info(v.msgid);
  if (v.version == 2 && (v.incompat_flags & kIncompatSigned) != 0) {
    const std::size_t at = crc_at + kChecksumSize;
    SignatureBlock s;
    s.link_id = frame[at];
    for (std::size_t i = 0; i < 6; ++i) {
      s.timestamp_10us |= static_cast<std::uint64_t>(frame[at + 1 + i]) << (8 * i);
      s.signature[i] = frame[at + 7 + i];
    }
    v.signature = s;
  }
  return v;
}

bool crc_matches(const FrameView& view) noexcept {
  const std::size_t covered = (view.version == 2 ? kHeaderSizeV2 : kHeaderSizeV1) - 1 + view.len;
  std::uint16_t crc = crc_accumulate(view.bytes.subspan(1, covered));
  crc = crc_accumulate(view.info->crc_extra, crc);
  return crc == view.crc;
}

}  // namespace detail

std::string_view to_string(FrameError error) noexcept {
  switch (error) {
    case FrameError::too_short:
      return "too_short";
    case FrameError::bad_magic:
      return "bad_magic";
    case FrameError::trailing_bytes:
      return "trailing_bytes";
    case FrameError::unknown_incompat_flags:
      return "unknown_incompat_flags";
    case FrameError::bad_crc:
      return "bad_crc";
  }
  return "?";
}

Frame encode(const Message& message, const FrameHeader& header, const SignParams* sign) noexcept {
  return std::visit([&](const auto& m) { return encode(m, header, sign); }, message);
}

std::optional<std::size_t> frame_size(std::span<const std::uint8_t> bytes) noexcept {
  return detail::announced_size(bytes);
}

Result<FrameView> parse_frame(std::span<const std::uint8_t> bytes) noexcept {
  const auto size = detail::announced_size(bytes);
  if (!size) return {FrameError::too_short, bytes.size()};
  if (*size == 0) return {FrameError::bad_magic, 0};
  if (bytes.size() < *size) return {FrameError::too_short, bytes.size()};
  if (bytes.size() > *size) return {FrameError::trailing_bytes, *size};
  FrameView view = detail::view_frame(bytes);
  if ((view.incompat_flags & ~kIncompatSigned) != 0) {
    return {FrameError::unknown_incompat_flags, 2};
  }
  if (view.info != nullptr && !detail::crc_matches(view)) {
    return {FrameError::bad_crc, bytes.size() - (view.is_signed() ? kSignatureSize : 0) - 2};
  }
  return view;
}

std::optional<Message> decode_message(const FrameView& frame) noexcept {
  if (frame.info == nullptr) return std::nullopt;
  return unpack_message(frame.msgid, frame.payload);
}

}  // namespace mocaplink::mavlink
