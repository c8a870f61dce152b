#include "mocaplink/mavlink/crc.hpp"

#include <array>
#include <cstring>

namespace mocaplink::mavlink {
namespace {

// The byte-wise update of mavlink-wire.md §2, tabulated for each value of (byte ^ crc_low).
constexpr std::uint16_t update_slow(std::uint8_t byte, std::uint16_t crc) {
  auto tmp = static_cast<std::uint8_t>(byte ^ static_cast<std::uint8_t>(crc & 0xFF));
  tmp = static_cast<std::uint8_t>(tmp ^ static_cast<std::uint8_t>(tmp << 4));
  return static_cast<std::uint16_t>((crc >> 8) ^ (tmp << 8) ^ (tmp << 3) ^ (tmp >> 4));
}

// Slicing-by-8 (the reflected-CRC variant of Intel's "slicing-by-N"): kTables[k][v] is the CRC
// contribution of byte value v followed by k zero bytes, so 8 input bytes fold with 8 independent
// lookups instead of a chain of 8 dependent ones. kTables[0] is the classic byte table.
constexpr std::array<std::array<std::uint16_t, 256>, 8> make_tables() {
  std::array<std::array<std::uint16_t, 256>, 8> t{};
  for (unsigned i = 0; i < 256; ++i) t[0][i] = update_slow(static_cast<std::uint8_t>(i), 0);
  for (std::size_t k = 1; k < 8; ++k) {
    for (unsigned i = 0; i < 256; ++i) {
      t[k][i] = static_cast<std::uint16_t>((t[k - 1][i] >> 8) ^ t[0][t[k - 1][i] & 0xFF]);
    }
  }
  return t;
}

constexpr auto kTables = make_tables();

inline std::uint16_t step(std::uint8_t byte, std::uint16_t crc) {
  return static_cast<std::uint16_t>((crc >> 8) ^ kTables[0][(byte ^ crc) & 0xFF]);
}

}  // namespace

std::uint16_t crc_accumulate(std::uint8_t byte, std::uint16_t crc) {
  return step(byte, crc);
}

std::uint16_t crc_accumulate(std::span<const std::uint8_t> bytes, std::uint16_t crc) {
  std::size_t i = 0;
  const std::size_t n = bytes.size();
  for (; i + 8 <= n; i += 8) {
    const auto b = bytes.subspan(i, 8);
    const auto lo = static_cast<std::uint8_t>(b[0] ^ (crc & 0xFF));
    const auto hi = static_cast<std::uint8_t>(b[1] ^ (crc >> 8));
    crc = static_cast<std::uint16_t>(kTables[7][lo] ^ kTables[6][hi] ^ kTables[5][b[2]] ^
                                     kTables[4][b[3]] ^ kTables[3][b[4]] ^ kTables[2][b[5]] ^
                                     kTables[1][b[6]] ^ kTables[0][b[7]]);
  }
  for (; i < n; ++i) crc = step(bytes[i], crc);
  return crc;
}

}  // namespace mocaplink::mavlink
