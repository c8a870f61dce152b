// DataStream packet framing (spec §3): tag u32 0x1A2B0001, body length u32, then items, each
// type u32 + payload length u32 + payload. Same format in both directions. Pure; thread-safe.
#pragma once

#include <cstddef>
#include <cstdint>
#include <span>
#include <vector>

#include "mocaplink/wire/vicon_items.hpp"
#include "mocaplink/wire/vicon_protocol.hpp"
#include "mocaplink/wire/vicon_result.hpp"

namespace mocaplink::wire::vicon {

/// Default cap on a packet body. The SDK has none (u32); a reader must have one so that an absurd
/// length cannot make it allocate gigabytes. 16 MiB is ~60 000 rigid bodies per frame.
inline constexpr std::uint32_t kDefaultMaxBodyBytes = 16u * 1024u * 1024u;

/// Validates an 8-byte packet header and returns the body length. Errors: fewer than 8 bytes,
/// wrong tag (the SDK ends the session on it), body length above `max_body_bytes`.
[[nodiscard]] Result<std::uint32_t> parse_packet_header(
    std::span<const std::byte> header, std::uint32_t max_body_bytes = kDefaultMaxBodyBytes);

/// One item of a packet body; `payload` points into the body passed to split_items.
struct RawItem {
  std::uint32_t type = 0;
  std::span<const std::byte> payload;
  std::size_t offset = 0;  ///< offset of the payload within the packet (header included)
};

/// Splits a packet body into its items. Errors: an item header or payload that runs past the end
/// of the body. An empty body is valid (no items). `base_offset` is added to offsets (use
/// kPacketHeaderBytes when `body` follows a header).
[[nodiscard]] Result<std::vector<RawItem>> split_items(
    std::span<const std::byte> body, std::size_t base_offset = kPacketHeaderBytes);

/// Builds one packet (header + items). Items appear in the order added.
class PacketBuilder {
 public:
  PacketBuilder();

  /// Appends an item with the payload encoded from `item`.
  template <Item T>
  PacketBuilder& add(const T& item) {
    const std::size_t start = begin_item(to_u32(T::kType));
    encode_item_payload(item, bytes_);
    end_item(start);
    return *this;
  }

  /// Appends an item with a ready-made payload (any type id, e.g. an unknown one in tests).
  PacketBuilder& add_raw(std::uint32_t type, std::span<const std::byte> payload);

  /// Number of items added so far.
  [[nodiscard]] std::size_t item_count() const { return items_; }

  /// The finished packet; the builder is left empty and reusable.
  [[nodiscard]] std::vector<std::byte> finish();

 private:
  std::size_t begin_item(std::uint32_t type);
  void end_item(std::size_t start);

  std::vector<std::byte> bytes_;
  std::size_t items_ = 0;
};

}  // namespace mocaplink::wire::vicon
