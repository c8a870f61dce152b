// MAVLink frames: encode typed messages into MAVLink 2 (or 1) frames, and check/decode one frame.
//
// Encoding (mavlink-wire.md §1–§3, §7):
//   Frame f = encode(msg, FrameHeader{.seq = s, .sysid = 1, .compid = 197});          // unsigned
//   const SignParams sp = signer.next(now_10us);  Frame f = encode(msg, header, &sp); // signed
//   std::size_t n = encode_into(msg, header, buffer);   // into a caller buffer, no Frame object
// MAVLink 2 frames are truncated (trailing zero payload bytes removed, at least 1 byte kept) and
// carry compat_flags 0. No heap allocation happens per frame. encode_v1 writes MAVLink 1 (base
// fields only, ids < 256).
//
// Decoding one frame whose boundaries are known (a UDP datagram holding one frame, a test vector):
//   Result<FrameView> r = parse_frame(bytes);   // magic, length, incompat flags, CRC
//   std::optional<Message> m = decode_message(*r);
// Byte streams go through StreamParser (stream_parser.hpp), which finds frame boundaries.
// Thread-safety: all functions here are pure and reentrant.
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>
#include <optional>
#include <span>
#include <string_view>
#include <variant>

#include "mocaplink/mavlink/messages.hpp"
#include "mocaplink/mavlink/signing.hpp"

namespace mocaplink::mavlink {

inline constexpr std::uint8_t kMagicV1 = 0xFE;
inline constexpr std::uint8_t kMagicV2 = 0xFD;
inline constexpr std::size_t kHeaderSizeV1 = 6;   ///< magic … msgid
inline constexpr std::size_t kHeaderSizeV2 = 10;  ///< magic … msgid (24 bit)
inline constexpr std::size_t kChecksumSize = 2;
inline constexpr std::size_t kSignatureSize = 13;  ///< link_id, timestamp[6], signature[6]
/// Only incompatibility flag defined by MAVLink 2; frames with any other bit are dropped (§4).
inline constexpr std::uint8_t kIncompatSigned = 0x01;
/// Largest MAVLink frame: signed MAVLink 2 with a 255-byte payload.
inline constexpr std::size_t kMaxFrameSize =
    kHeaderSizeV2 + 255 + kChecksumSize + kSignatureSize;  // 280

/// Sender identity and sequence number of one frame (seq wraps 255 → 0 per sender, §5; use
/// SequenceCounter). sysid and compid 0 are invalid as sources but are not rejected here.
struct FrameHeader {
  std::uint8_t seq = 0;
  std::uint8_t sysid = 0;
  std::uint8_t compid = 0;
};

/// A complete encoded frame in fixed storage (no heap). size() == 0 means "not encoded" (only
/// encode_v1 of a message with id ≥ 256 produces that).
class Frame {
 public:
  [[nodiscard]] std::span<const std::uint8_t> bytes() const noexcept {
    return {data_.data(), size_};
  }
  [[nodiscard]] std::size_t size() const noexcept { return size_; }
  [[nodiscard]] bool empty() const noexcept { return size_ == 0; }
  /// Whole storage (kMaxFrameSize), for encode_into; then set_size.
  [[nodiscard]] std::span<std::uint8_t, kMaxFrameSize> storage() noexcept { return data_; }
  void set_size(std::size_t n) noexcept { size_ = n <= kMaxFrameSize ? n : 0; }

 private:
  std::array<std::uint8_t, kMaxFrameSize> data_;
  std::size_t size_ = 0;
};

namespace detail {
/// Completes a MAVLink 2 frame whose untruncated payload (max_length bytes) is already at
/// out[10…]: truncates, writes header, CRC and optional signature. Returns the frame size.
std::size_t finish_v2(std::span<std::uint8_t, kMaxFrameSize> out, std::uint32_t msgid,
                      std::uint8_t crc_extra, std::size_t max_length, const FrameHeader& header,
                      const SignParams* sign) noexcept;
/// Completes a MAVLink 1 frame whose base payload (base_length bytes) is at out[6…].
std::size_t finish_v1(std::span<std::uint8_t, kMaxFrameSize> out, std::uint8_t msgid,
                      std::uint8_t crc_extra, std::size_t base_length,
                      const FrameHeader& header) noexcept;
}  // namespace detail

/// Encodes `msg` as a MAVLink 2 frame into `out`, signed if `sign` is non-null (its key is used,
/// its timestamp written as is). Returns the frame size (12 + len, + 13 if signed).
template <typename M>
std::size_t encode_into(const M& msg, const FrameHeader& header,
                        std::span<std::uint8_t, kMaxFrameSize> out,
                        const SignParams* sign = nullptr) noexcept {
  msg.pack(out.template subspan<kHeaderSizeV2, M::kMaxLength>());
  return detail::finish_v2(out, M::kId, M::kCrcExtra, M::kMaxLength, header, sign);
}

/// Encodes `msg` as a MAVLink 2 frame (see encode_into).
template <typename M>
[[nodiscard]] Frame encode(const M& msg, const FrameHeader& header,
                           const SignParams* sign = nullptr) noexcept {
  Frame frame;
  frame.set_size(encode_into(msg, header, frame.storage(), sign));
  return frame;
}

/// Encodes whichever message `message` holds as a MAVLink 2 frame.
[[nodiscard]] Frame encode(const Message& message, const FrameHeader& header,
                           const SignParams* sign = nullptr) noexcept;

/// Encodes `msg` as a MAVLink 1 frame (base fields only, no truncation, never signed); an empty
/// Frame if the message id does not fit MAVLink 1's 8-bit id.
template <typename M>
[[nodiscard]] Frame encode_v1(const M& msg, const FrameHeader& header) noexcept {
  Frame frame;
  if constexpr (M::kId < 256) {
    std::array<std::uint8_t, M::kMaxLength> full{};
    msg.pack(full);
    auto out = frame.storage();
    for (std::size_t i = 0; i < M::kBaseLength; ++i) out[kHeaderSizeV1 + i] = full[i];
    frame.set_size(detail::finish_v1(out, static_cast<std::uint8_t>(M::kId), M::kCrcExtra,
                                     M::kBaseLength, header));
  }
  return frame;
}

/// Signature block of a signed MAVLink 2 frame (§7.1).
struct SignatureBlock {
  std::uint8_t link_id = 0;
  std::uint64_t timestamp_10us = 0;  ///< 48-bit
  std::array<std::uint8_t, 6> signature{};
};

/// One frame checked at the framing level. Views into the caller's bytes (valid as long as they).
struct FrameView {
  std::uint8_t version = 2;  ///< 1 (0xFE) or 2 (0xFD)
  std::uint8_t len = 0;      ///< payload length on the wire
  std::uint8_t incompat_flags = 0;
  std::uint8_t compat_flags = 0;
  std::uint8_t seq = 0;
  std::uint8_t sysid = 0;
  std::uint8_t compid = 0;
  std::uint32_t msgid = 0;
  std::uint16_t crc = 0;              ///< checksum as received
  const MessageInfo* info = nullptr;  ///< nullptr: unknown message id, CRC not checkable (§2)
  std::optional<SignatureBlock> signature;  ///< present iff incompat_flags & kIncompatSigned
  std::span<const std::uint8_t> payload;    ///< len bytes
  std::span<const std::uint8_t> bytes;      ///< the whole frame, signature included

  [[nodiscard]] bool is_signed() const noexcept { return signature.has_value(); }
  [[nodiscard]] bool known() const noexcept { return info != nullptr; }
};

/// Why parse_frame rejected bytes (the stream parser counts the same reasons).
enum class FrameError : std::uint8_t {
  too_short,               ///< fewer bytes than the header or the length byte announces
  bad_magic,               ///< first byte is neither 0xFE nor 0xFD
  trailing_bytes,          ///< more bytes than one frame (parse_frame wants exactly one)
  unknown_incompat_flags,  ///< incompat bits other than 0x01 (§4): must be dropped
  bad_crc,                 ///< CRC mismatch for a known message id
};
[[nodiscard]] std::string_view to_string(FrameError error) noexcept;

/// Either a value or a FrameError with the byte offset where it was detected.
template <typename T>
class [[nodiscard]] Result {
 public:
  Result(T value) : value_(std::move(value)) {}  // NOLINT(google-explicit-constructor)
  Result(FrameError error, std::size_t offset) : value_(std::in_place_index<1>, error, offset) {}

  [[nodiscard]] bool ok() const noexcept { return value_.index() == 0; }
  explicit operator bool() const noexcept { return ok(); }
  [[nodiscard]] const T& value() const { return std::get<0>(value_); }
  [[nodiscard]] const T& operator*() const { return value(); }
  [[nodiscard]] const T* operator->() const { return &value(); }
  [[nodiscard]] FrameError error() const { return std::get<1>(value_).error; }
  [[nodiscard]] std::size_t error_offset() const { return std::get<1>(value_).offset; }

 private:
  struct Error {
    Error(FrameError e, std::size_t o) : error(e), offset(o) {}
    FrameError error;
    std::size_t offset;
  };
  std::variant<T, Error> value_;
};

/// Total size of the frame starting at bytes[0], from its header: 0 if bytes[0] is not a magic,
/// nullopt if more bytes are needed to know (MAVLink 2 needs 3 bytes: magic, len, incompat).
[[nodiscard]] std::optional<std::size_t> frame_size(std::span<const std::uint8_t> bytes) noexcept;

/// Checks that `bytes` is exactly one MAVLink 1 or 2 frame: magic, length, incompat flags, CRC
/// (when the message id is known; unknown ids give a FrameView with info == nullptr). Does not
/// verify signatures (SigningKey::verify, SignatureVerifier).
[[nodiscard]] Result<FrameView> parse_frame(std::span<const std::uint8_t> bytes) noexcept;

/// The typed message in a frame from parse_frame or StreamParser: payload zero-filled to the
/// message's full length (MAVLink 1 and truncated frames), extra bytes ignored. nullopt for an
/// unknown message id.
[[nodiscard]] std::optional<Message> decode_message(const FrameView& frame) noexcept;

}  // namespace mocaplink::mavlink
