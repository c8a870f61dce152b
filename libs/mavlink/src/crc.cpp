#include "mocaplink/mavlink/crc.hpp"

#include <array>

namespace mocaplink::mavlink {
namespace {

// The byte-wise update of mavlink-wire.md §2, tabulated for each value of (byte ^ crc_low).
constexpr std::uint16_t update_slow(std::uint8_t byte, std::uint16_t crc) {
  auto tmp = static_cast<std::uint8_t>(byte ^ static_cast<std::uint8_t>(crc & 0xFF));
  tmp = static_cast<std::uint8_t>(tmp ^ static_cast<std::uint8_t>(tmp << 4));
  return static_cast<std::uint16_t>((crc >> 8) ^ (tmp << 8) ^ (tmp << 3) ^ (tmp >> 4));
}

constexpr std::array<std::uint16_t, 256> make_table() {
  std::array<std::uint16_t, 256> table{};
  for (unsigned i = 0; i < 256; ++i) table[i] = update_slow(static_cast<std::uint8_t>(i), 0);
  return table;
}

constexpr auto kTable = make_table();

}  // namespace

std::uint16_t crc_accumulate(std::uint8_t byte, std::uint16_t crc) {
  return static_cast<std::uint16_t>((crc >> 8) ^ kTable[(byte ^ crc) & 0xFF]);
}

std::uint16_t crc_accumulate(std::span<const std::uint8_t> bytes, std::uint16_t crc) {
  for (const std::uint8_t b : bytes) crc = crc_accumulate(b, crc);
  return crc;
}

}  // namespace mocaplink::mavlink
