// Robust MAVLink 1/2 frame extraction from untrusted bytes (mavlink-wire.md §8).
//
//   StreamParser parser(&verifier);             // verifier optional (nullptr: no signing policy)
//   parser.feed(bytes, now_10us, [&](const FrameView& f) { ... decode_message(f) ... });
//   parser.feed_datagram(datagram, now_10us, on_frame);   // UDP: frames never span datagrams
//
// Behaviour:
// * Scans for 0xFD / 0xFE; bytes before a magic are counted as garbage_bytes.
// * A rejected candidate (bad CRC, unknown incompat bit on a frame whose CRC cannot vouch for it,
//   incomplete at the end of a datagram) resumes the search ONE byte after its magic, so a fake
//   magic whose claimed length covers the next valid frame does not swallow it (§8).
// * A frame of an unknown message id cannot be CRC-checked (§2): it is delivered as a raw frame
//   (FrameView::info == nullptr) and counted in unknown_msgid — unless a CRC-valid known frame
//   starts inside it, in which case it is treated as garbage and the search resumes after its
//   magic (the known frame wins).
// * A CRC-valid frame with unknown incompatibility bits is dropped whole (unknown_incompat).
// * With a SignatureVerifier, each framed message is checked against the link's signing policy
//   (replay, 60 s rule, unsigned policy); rejected frames are dropped whole and counted by reason.
//   Without one, signed frames are delivered unverified and unsigned frames accepted.
// * Memory is bounded: a fixed internal buffer (kStreamBufferSize), no allocation.
// Frames passed to the callback view the parser's buffer (or the datagram) and are valid only
// during the callback. Not thread-safe: one parser per link, driven by one thread.
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>
#include <optional>
#include <span>
#include <string_view>

#include "mocaplink/mavlink/frame.hpp"
#include "mocaplink/mavlink/signing.hpp"

namespace mocaplink::mavlink {

/// Per-reason counts since construction (monotonic, never reset by the parser).
struct ParserCounters {
  std::uint64_t frames = 0;             ///< delivered to the callback (known + unknown ids)
  std::uint64_t v1_frames = 0;          ///< delivered MAVLink 1 frames
  std::uint64_t signed_frames = 0;      ///< delivered signed MAVLink 2 frames
  std::uint64_t unknown_msgid = 0;      ///< delivered raw: message id unknown, CRC unchecked
  std::uint64_t garbage_bytes = 0;      ///< bytes skipped while searching for a magic
  std::uint64_t bad_crc = 0;            ///< candidates with a known id and a wrong CRC
  std::uint64_t unknown_incompat = 0;   ///< frames with incompat bits other than 0x01
  std::uint64_t bad_signature = 0;      ///< signed, hash mismatch (verifier)
  std::uint64_t replay = 0;             ///< timestamp not newer than the stream's (verifier)
  std::uint64_t stale_new_stream = 0;   ///< new stream > 60 s behind local time (verifier)
  std::uint64_t unsigned_rejected = 0;  ///< unsigned while signing is required (verifier)
  std::uint64_t too_many_streams = 0;   ///< signing stream table full (verifier)
  std::uint64_t truncated_tail = 0;     ///< datagrams / finish() calls ending mid-frame

  /// Calls f(std::string_view name, std::uint64_t value) for every counter, in declaration
  /// order (names = member names), for logs and JSON.
  template <typename F>
  void for_each(F&& f) const {
    f("frames", frames);
    f("v1_frames", v1_frames);
    f("signed_frames", signed_frames);
    f("unknown_msgid", unknown_msgid);
    f("garbage_bytes", garbage_bytes);
    f("bad_crc", bad_crc);
    f("unknown_incompat", unknown_incompat);
    f("bad_signature", bad_signature);
    f("replay", replay);
    f("stale_new_stream", stale_new_stream);
    f("unsigned_rejected", unsigned_rejected);
    f("too_many_streams", too_many_streams);
    f("truncated_tail", truncated_tail);
  }
  bool operator==(const ParserCounters&) const = default;
};

/// Bytes the stream parser keeps between feed() calls (≥ 2 × kMaxFrameSize).
inline constexpr std::size_t kStreamBufferSize = 2048;

class StreamParser {
 public:
  /// `verifier` (optional, not owned, must outlive the parser) applies the link's signing policy.
  explicit StreamParser(SignatureVerifier* verifier = nullptr) noexcept : verifier_(verifier) {}

  /// Byte-stream input (serial, TCP): any chunking; a frame may span calls. `now_10us` is the
  /// local signing time (only used with a verifier). Calls on_frame(const FrameView&) per
  /// accepted frame, in stream order.
  template <typename OnFrame>
  void feed(std::span<const std::uint8_t> bytes, std::uint64_t now_10us, OnFrame&& on_frame) {
    while (!bytes.empty()) {
      bytes = bytes.subspan(append(bytes));
      while (const auto frame = next_buffered(now_10us)) on_frame(*frame);
      compact();
    }
  }

  /// One UDP datagram (several frames allowed, none spanning datagrams). Independent of feed()'s
  /// buffer. An incomplete frame at the end counts one truncated_tail.
  template <typename OnFrame>
  void feed_datagram(std::span<const std::uint8_t> datagram, std::uint64_t now_10us,
                     OnFrame&& on_frame) {
    std::size_t pos = 0;
    bool truncated = false;
    while (const auto frame = next_in(datagram, pos, true, truncated, now_10us)) on_frame(*frame);
    if (truncated) ++counters_.truncated_tail;
  }

  /// End of a byte stream (connection closed): a pending partial frame counts one
  /// truncated_tail; complete frames hidden behind a rejected partial one are still delivered.
  template <typename OnFrame>
  void finish(std::uint64_t now_10us, OnFrame&& on_frame) {
    bool truncated = false;
    const std::span<const std::uint8_t> pending{buffer_.data(), size_};
    while (const auto frame = next_in(pending, start_, true, truncated, now_10us)) on_frame(*frame);
    if (truncated) ++counters_.truncated_tail;
    start_ = size_ = 0;
  }

  [[nodiscard]] const ParserCounters& counters() const noexcept { return counters_; }
  /// Bytes waiting for the rest of a frame.
  [[nodiscard]] std::size_t pending_bytes() const noexcept { return size_ - start_; }

 private:
  std::size_t append(std::span<const std::uint8_t> bytes) noexcept;
  std::optional<FrameView> next_buffered(std::uint64_t now_10us) noexcept;
  void compact() noexcept;
  /// Next accepted frame in bytes[pos…]; advances pos past consumed bytes. `final`: no more bytes
  /// will come (incomplete candidates are rejected, `truncated` set). nullopt when more bytes are
  /// needed (not final) or nothing is left (final).
  std::optional<FrameView> next_in(std::span<const std::uint8_t> bytes, std::size_t& pos,
                                   bool final, bool& truncated, std::uint64_t now_10us) noexcept;
  bool policy_accepts(const FrameView& frame, std::uint64_t now_10us) noexcept;

  SignatureVerifier* verifier_;
  ParserCounters counters_;
  std::array<std::uint8_t, kStreamBufferSize> buffer_{};
  std::size_t start_ = 0;  // first unconsumed byte
  std::size_t size_ = 0;   // bytes held
};

}  // namespace mocaplink::mavlink
