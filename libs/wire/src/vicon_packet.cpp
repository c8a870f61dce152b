#include "mocaplink/wire/vicon_packet.hpp"

#include <string>

namespace mocaplink::wire::vicon {

Result<std::uint32_t> parse_packet_header(std::span<const std::byte> header,
                                          std::uint32_t max_body_bytes) {
  ByteReader r(header);
  const auto tag = r.read<std::uint32_t>();
  const auto length = r.read<std::uint32_t>();
  if (!tag || !length) return parse_error(0, "packet header shorter than 8 bytes");
  if (*tag != kPacketTag) {
    return parse_error(0, "bad packet tag " + std::to_string(*tag) + " (expected 0x1A2B0001)");
  }
  if (*length > max_body_bytes) {
    return parse_error(4, "packet body length " + std::to_string(*length) + " exceeds the cap of " +
                              std::to_string(max_body_bytes) + " bytes");
  }
  return *length;
}

Result<std::vector<RawItem>> split_items(std::span<const std::byte> body, std::size_t base_offset) {
  ByteReader r(body);
  std::vector<RawItem> items;
  while (!r.empty()) {
    const std::size_t at = base_offset + r.offset();
    const auto type = r.read<std::uint32_t>();
    const auto length = r.read<std::uint32_t>();
    if (!type || !length) return parse_error(at, "truncated item header");
    auto payload = r.bytes(*length);
    if (!payload) {
      return parse_error(at + 4, item_type_name(*type) + " payload length " +
                                     std::to_string(*length) + " runs past the packet end (" +
                                     std::to_string(r.remaining()) + " bytes left)");
    }
    items.push_back(RawItem{*type, *payload, at + kItemHeaderBytes});
  }
  return items;
}

PacketBuilder::PacketBuilder() {
  codec::Writer w(bytes_);
  w.put(kPacketTag);
  w.put(std::uint32_t{0});
}

PacketBuilder& PacketBuilder::add_raw(std::uint32_t type, std::span<const std::byte> payload) {
  const std::size_t start = begin_item(type);
  codec::Writer(bytes_).put_bytes(payload);
  end_item(start);
  return *this;
}

std::size_t PacketBuilder::begin_item(std::uint32_t type) {
  codec::Writer w(bytes_);
  w.put(type);
  const std::size_t start = bytes_.size();
  w.put(std::uint32_t{0});
  return start;
}

void PacketBuilder::end_item(std::size_t start) {
  codec::Writer(bytes_).patch_u32(start, static_cast<std::uint32_t>(bytes_.size() - start - 4));
  ++items_;
}

std::vector<std::byte> PacketBuilder::finish() {
  codec::Writer(bytes_).patch_u32(4, static_cast<std::uint32_t>(bytes_.size() - 8));
  std::vector<std::byte> out;
  out.swap(bytes_);
  items_ = 0;
  codec::Writer w(bytes_);
  w.put(kPacketTag);
  w.put(std::uint32_t{0});
  return out;
}

}  // namespace mocaplink::wire::vicon
